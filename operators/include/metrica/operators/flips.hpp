// The reconnection flips of the seed (section 3.1), as replacements of a
// small cavity (cavity.hpp):
//
//   2-3  the face cde shared by tets abc-side a and b becomes the edge ab
//        with three tets around it;
//   3-2, 4-4, n -> 2n-4  (edge removal) the shell of an inner edge ab with
//        ring v0..v(n-1) is replaced by a triangulation of the ring, each
//        triangle joined to a and to b; n = 3 is the 3-2 flip, n = 4 the
//        4-4 flip. The triangulations tried are the n fans of the ring
//        (for n <= 5 these are all of them);
//   2-2  on the boundary: a boundary edge ab whose two boundary faces lie
//        on one surface id (not a ridge) and whose shell has two tets
//        around ring vertex x is swapped for the edge v0 v2 (more generally
//        an open shell of n tets, ring v0..vn, becomes the fans of the
//        polygon v0..vn). The new boundary faces must fit the Geometry
//        (NoGeometry: stay in the old faces' plane, normal deviation below
//        a tolerance, so the volume is conserved; CadGeometry: follow the
//        model's normal).
//
// Each flip is an operation (operation.hpp): find (read connectivity),
// decide (orientation with the Precision, the Criterion, the shape floor)
// and, when it says yes, apply. The pass runner holds the locks.
#pragma once

#include <metrica/geometry.hpp>
#include <metrica/geometry/model.hpp>
#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/cavity.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/operators/work_list.hpp>
#include <metrica/predicates/precision.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace metrica {

struct FlipOptions {
  // Largest shell an edge removal tries (the ring's fans grow as n).
  int max_shell = 7;
  // Edge removals not tried: an edge of metric length below
  // short_edge_ring4 with a ring of 4 vertices, below short_edge_ring5
  // with 5 or more (0: every edge is tried). The new tets are the ring's
  // triangles joined to a and b, flat when ab is short against its ring
  // (few such removals are applied: docs/benchmarks.md).
  double short_edge_ring4 = 0.0;
  double short_edge_ring5 = 0.0;
  // Under a criterion scored by the mean ratio (MinQuality), an edge
  // removal is not tried when the shell's worst tet is at or above
  // good_shell[n], n the ring's size (the last entry for larger rings; 1:
  // always tried). A ring's triangles joined to a and b are flatter the
  // larger the ring, so a good shell of a large ring is rarely beaten
  // (docs/benchmarks.md, "Why the defaults").
  std::array<double, 8> good_shell{1, 1, 1, 1, 1, 1, 1, 1};
  // Boundary faces of a 2-2 flip: largest angle between old and new
  // normals, as 1 - cos (flat surfaces: round-off only).
  double max_normal_deviation = 1e-9;
  double shape_floor = ShapeFloors::flip;
};

// The ring of edge ab from its shell (append_ring: tet k of the shell is
// (a, b, v_k, v_{k+1})). Returns the orientation sign of (a, b, v0, v1).
inline int edge_ring(const Mesh& mesh, VertexId a, VertexId b, const Shell& shell, VertexList& ring) {
  ring.clear();
  append_ring(mesh, a, b, shell, ring);
  return permutation_sign(mesh.tet(shell.tets[0]), a, b, ring[0], ring[1]);
}

// The tets of the fan of polygon `ring` from vertex k, each triangle
// joined to a and b, oriented positively given the ring's sign.
inline void fan_tets(const VertexList& ring, std::size_t k, VertexId a, VertexId b, int sign, NewTets& out) {
  const std::size_t m = ring.size();
  if (m < 3) {
    out.clear();
    return;
  }
  // Sized once and written in place (push_back's checks were most of the
  // cost of this function, called for every fan of every edge removal).
  out.resize(2 * (m - 2), boost::container::default_init);
  const VertexId first = sign > 0 ? b : a, second = sign > 0 ? a : b;
  for (std::size_t i = 1; i + 1 < m; ++i) {
    const VertexId p = ring[k], q = ring[(k + i) % m], r = ring[(k + i + 1) % m];
    out[2 * (i - 1)] = {p, q, r, first};
    out[2 * (i - 1) + 1] = {q, p, r, second};
  }
}

inline bool all_positive(const Mesh& mesh, std::span<const TetVertices> tets) {
  for (const auto& t : tets)
    if (!positive_tet(mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2]), mesh.point(t[3]))) return false;
  return true;
}

inline void tet_vertices_of(const Mesh& mesh, std::span<const TetId> ids, NewTets& out) {
  out.clear();
  for (TetId t : ids) out.emplace_back(mesh.tet(t));
}

// Scratch space of one worker, reused across calls (no allocation).
struct FlipScratch : ScratchGeneration {
  TetList ball;
  Shell shell;
  VertexList ring;
  NewTets old_tets, candidate, best;
  // The scores of best's tets (scored criteria; empty when not kept).
  boost::container::small_vector<double, 32> best_scores;
  CavityPlan plan;
  TetList created;
  // Edge removal: orientation (0 unknown, 1 positive, -1 not) and score
  // (NaN unknown) of ring triangle x joined to apex slot j, at 2 x + j,
  // for rings of up to kMemoRing vertices.
  static constexpr std::size_t kMemoRing = 8;
  static constexpr std::size_t kTriangles = kMemoRing * (kMemoRing - 1) * (kMemoRing - 2) / 6;
  std::array<std::int8_t, 2 * kTriangles> memo_orientation{};
  std::array<double, 2 * kTriangles> memo_score{};
  void clear_memo() {
    memo_orientation.fill(0);
    memo_score.fill(std::numeric_limits<double>::quiet_NaN());
  }
  // The combinatorial number of the set {p, q, r} of ring positions.
  static std::size_t triangle_index(std::size_t p, std::size_t q, std::size_t r) {
    if (p > q) std::swap(p, q);
    if (q > r) std::swap(q, r);
    if (p > q) std::swap(p, q);
    return r * (r - 1) * (r - 2) / 6 + q * (q - 1) / 2 + p;
  }
};

// Edge removal of ab (3-2, 4-4, n -> 2n-4) or, on the boundary, the 2-2
// flip: the best fan of the ring is in s.best, its cavity plan in s.plan.
struct EdgeRemovalPlan {
  VertexId a = kNoId, b = kNoId;
  int ref = 0;
};

namespace detail {

// Whether the removal of ab (shell `shell`) is one to weigh: one material,
// not a short edge with a large ring (FlipOptions::short_edge_ring*), a
// shell within max_shell; open (on the boundary): an inner edge of one
// surface, whose id goes to `surface` (0 for a closed shell).
template <MetricSpace S>
bool edge_removal_applies(const Mesh& mesh, VertexId a, VertexId b, const Shell& shell, const FlipOptions& o,
                          SurfaceId& surface) {
  const std::size_t n = shell.tets.size();
  const int ref = mesh.tet_ref(shell.tets[0]);
  for (TetId t : shell.tets)
    if (mesh.tet_ref(t) != ref) return false;
  if (mesh.is_required_edge(a, b)) return false;
  surface = 0;
  const std::size_t ring_size = shell.closed ? n : n + 1;
  if (ring_size >= 4) {
    const double shortest = ring_size == 4 ? o.short_edge_ring4 : o.short_edge_ring5;
    if (shortest > 0.0 && !S::edge_length_in(mesh, a, b, {shortest, std::numeric_limits<double>::infinity()}))
      return false;
  }
  if (shell.closed) return n >= 3 && static_cast<int>(n) <= o.max_shell;
  if (n < 2 || static_cast<int>(n) + 1 > o.max_shell || mesh.is_ridge(a, b) || mesh.keeps_surface()) return false;
  // The two boundary faces through ab, on one surface.
  SurfaceId ids[2] = {0, 0};
  int k = 0;
  for (TetId t : {shell.tets.front(), shell.tets.back()})
    for (int f = 0; f < 4; ++f) {
      const VertexId opp = mesh.tet(t)[f];
      if (opp == a || opp == b || mesh.neighbour(t, f).valid()) continue;
      if (k < 2) ids[k] = mesh.surface_id(t, f);
      ++k;
    }
  if (k != 2 || ids[0] != ids[1] || ids[0] <= 0) return false;
  surface = ids[0];
  return true;
}

// The boundary 2-2 flip's new facets (on the closing edge v_n v_0 of the
// ring, in s.candidate) fit the Geometry where the old ones were.
template <Geometry G>
bool boundary_fan_fits(const Mesh& mesh, VertexId a, VertexId b, const FlipScratch& s, SurfaceId surface,
                       const FlipOptions& o, const G& geometry) {
  const Eigen::Vector3d n_old = face_normal(mesh, a, b, s.ring.front());
  bool flat = geometry.facet_fits(mesh, a, b, s.ring.back(), surface, n_old, o.max_normal_deviation);
  for (const auto& t : s.candidate)
    for (int f = 0; f < 4 && flat; ++f) {
      const VertexId opposite = t[f];
      const bool closing = local_index(t, s.ring.front()) >= 0 && local_index(t, s.ring.back()) >= 0 &&
                           opposite != s.ring.front() && opposite != s.ring.back() && opposite != a && opposite != b;
      if (!closing) continue;
      const auto fv = face_vertices(t, f);
      flat = geometry.facet_fits(mesh, fv[0], fv[1], fv[2], surface, n_old, o.max_normal_deviation);
    }
  return flat;
}

// The boundary 2-2 flip's new boundary edge v_n v_0 does not exist yet
// (it can only on a surface folded by round-off, but then the flip would
// double a face).
inline bool closing_edge_is_new(const Mesh& mesh, FlipScratch& s) {
  return tet_with_edge(mesh, s.ring.front(), s.ring.back(), s.ball) == kNoId;
}

// Whether x and y are next to each other on the ring (cyclically).
inline bool ring_neighbours(const VertexList& ring, VertexId x, VertexId y) {
  const std::size_t m = ring.size();
  for (std::size_t i = 0; i < m; ++i)
    if (ring[i] == x) return ring[(i + 1) % m] == y || ring[(i + m - 1) % m] == y;
  return false;
}

// The new inner faces of an edge removal ab: the triangles of the chosen
// ring triangulation (s.best: tets (p, q, r, apex) two by two, the apex a
// or b), and each of its diagonals joined to a and to b. One whose
// vertices are all on the boundary may already be a face outside the
// shell: a boundary vertex whose umbrella is three triangles (a spike)
// folded against the shell, its base a ring triangle or a diagonal with a
// or b, where the removal would put that face on three tets. No shell tet
// holds either kind (a shell tet holds two ring vertices next on the ring),
// so any tet holding one is outside.
inline bool ring_faces_are_new(const Mesh& mesh, FlipScratch& s) {
  const auto on_boundary = [&](VertexId v) { return mesh.vertex_class(v) != VertexClass::interior; };
  for (std::size_t c = 0; c < s.best.size(); ++c) {
    const TetVertices t = s.best[c];
    // The ring triangle, once for its two tets.
    if (c % 2 == 0 && on_boundary(t[0]) && on_boundary(t[1]) && on_boundary(t[2]) &&
        tet_with_face(mesh, t[0], t[1], t[2], s.ball) != kNoId)
      return false;
    // A diagonal (two ring vertices not next on the ring; the open ring's
    // closing edge is new, checked before) with the apex.
    const VertexId apex = t[3];
    if (!on_boundary(apex)) continue;
    for (int i = 0; i < 3; ++i) {
      const VertexId x = t[i], y = t[(i + 1) % 3];
      if (!on_boundary(x) || !on_boundary(y) || ring_neighbours(s.ring, x, y)) continue;
      if (tet_with_face(mesh, apex, x, y, s.ball) != kNoId) return false;
    }
  }
  return true;
}

}  // namespace detail

// Decide the removal of ab; its shell is in s.shell (edge_shell). Each fan
// of the ring (the new tets joining a ring triangulation to a and b) is
// weighed in turn: positive (P), on the boundary fitting the Geometry,
// better than the best so far under the criterion, above the shape floor.
template <MetricSpace S, class Criterion, Geometry G = ModelOrFacets>
Decision<EdgeRemovalPlan> decide_edge_removal(const Mesh& mesh, VertexId a, VertexId b, FlipScratch& s,
                                              const FlipOptions& o, const G& geometry = {}) {
  const Shell& shell = s.shell;
  const Acceptance<S, Criterion> accept(o.shape_floor);
  SurfaceId surface = 0;
  if (!detail::edge_removal_applies<S>(mesh, a, b, shell, o, surface)) return Refusal::not_applicable;
  const int ref = mesh.tet_ref(shell.tets[0]);
  const int sign = edge_ring(mesh, a, b, shell, s.ring);
  const std::size_t m = s.ring.size();
  // For a triangle of 3 or 4 ring vertices the fans repeat (the 3 fans of a
  // triangle are one, fans k and k + 2 of a quad are one).
  const std::size_t fans = m == 3 ? 1 : m == 4 ? 2 : m;
  // Scored criteria: the shell is scored once; each new tet (a ring
  // triangle joined to a or b, shared by several fans) is oriented and
  // scored at most once, in s.memo, by the triangle's combinatorial index.
  constexpr bool scored = ScoredCriterion<Criterion>;
  const bool memo = scored && m <= FlipScratch::kMemoRing;
  double best_score = 0.0;
  if constexpr (scored) {
    best_score = min_score_of<Criterion, S>(mesh, view(shell.tets));
    if constexpr (CriterionTraits<Criterion>::score_is_mean_ratio_cubed) {
      const double good = o.good_shell[std::min(m, o.good_shell.size() - 1)];
      if (best_score >= good * good * good) return Refusal::not_applicable;
    }
    if (memo) s.clear_memo();
  } else {
    tet_vertices_of(mesh, view(shell.tets), s.old_tets);
  }
  bool found = false;
  s.best_scores.clear();
  for (std::size_t k = 0; k < fans; ++k) {
    fan_tets(s.ring, k, a, b, sign, s.candidate);
    // Tet c of the candidate is triangle (k, k + i, k + i + 1), i = 1 + c / 2,
    // joined to the apex of slot c % 2 (fan_tets' order).
    auto slot = [&](std::size_t c) {
      const std::size_t i = 1 + c / 2;
      return 2 * FlipScratch::triangle_index(k, (k + i) % m, (k + i + 1) % m) + c % 2;
    };
    bool positive = true;
    for (std::size_t c = 0; c < s.candidate.size() && positive; ++c) {
      const auto& t = s.candidate[c];
      auto orient = [&] {
        return positive_tet(mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2]), mesh.point(t[3])) ? 1 : -1;
      };
      if (memo) {
        auto& o8 = s.memo_orientation[slot(c)];
        if (o8 == 0) o8 = orient() > 0 ? 1 : -1;
        positive = o8 > 0;
      } else {
        positive = orient() > 0;
      }
    }
    if (!positive) continue;
    if (!shell.closed && !detail::boundary_fan_fits(mesh, a, b, s, surface, o, geometry)) continue;
    if constexpr (scored) {
      const double bar = Criterion::bar(best_score);
      double q = std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < s.candidate.size() && q > bar; ++c) {
        if (memo) {
          double& score = s.memo_score[slot(c)];
          if (std::isnan(score)) score = Criterion::template tet_score<S>(mesh, s.candidate[c]);
          q = std::min(q, score);
        } else {
          q = std::min(q, Criterion::template tet_score<S>(mesh, s.candidate[c]));
        }
      }
      if (q <= bar) continue;
      best_score = q;
    } else {
      const NewTets& reference = found ? s.best : s.old_tets;
      if (!Criterion::template prefers<S>(mesh, view(reference), view(s.candidate))) continue;
    }
    if (!accept.keeps_shape(mesh, view(shell.tets), view(s.candidate))) continue;
    s.best = s.candidate;
    s.best_scores.clear();
    if (memo)
      for (std::size_t c = 0; c < s.candidate.size(); ++c) s.best_scores.emplace_back(s.memo_score[slot(c)]);
    found = true;
  }
  if (!found) return Refusal::rejected;
  if (!shell.closed && !detail::closing_edge_is_new(mesh, s)) return Refusal::rejected;
  if (!detail::ring_faces_are_new(mesh, s)) return Refusal::rejected;
  if (!plan_cavity(mesh, view(shell.tets), view(s.best), s.plan, kNoId, kNoId, surface)) return Refusal::rejected;
  return EdgeRemovalPlan{a, b, ref};
}

template <MetricSpace S, class Criterion>
void apply_edge_removal(Mesh& mesh, const EdgeRemovalPlan& plan, FlipScratch& s) {
  apply_cavity(mesh, view(s.shell.tets), view(s.best), s.plan, plan.ref, s.created);
  Acceptance<S, Criterion>::after_apply(mesh, view(s.created), view(s.best_scores));
}

// The 2-3 flip of the inner face `face` of tet t: the two tets sharing it
// become three around the edge joining their apexes (s.candidate, with
// their scores in s.best_scores and the cavity plan in s.plan).
struct Flip23Plan {
  TetId t = kNoId, other = kNoId;
  int face = -1;
};

template <MetricSpace S, class Criterion>
Decision<Flip23Plan> decide_flip23(const Mesh& mesh, TetId t, int face, FlipScratch& s, const FlipOptions& o) {
  const FaceRef nb = mesh.neighbour(t, face);
  if (!nb.valid() || mesh.tet_ref(nb.tet()) != mesh.tet_ref(t)) return Refusal::not_applicable;
  const TetVertices tv = mesh.tet(t);
  const VertexId a = tv[face];
  const VertexId b = mesh.tet(nb.tet())[nb.face()];
  const auto f = face_vertices(tv, face);  // outward from t, so a sees it negatively
  // The face's normal points from a to b, so (p, q, a, b) is positive for
  // each of its edges pq taken in the face's order.
  s.candidate.clear();
  for (int i = 0; i < 3; ++i) {
    const VertexId p = f[i], q = f[(i + 1) % 3];
    s.candidate.emplace_back(TetVertices{p, q, a, b});
  }
  if (!all_positive(mesh, view(s.candidate))) return Refusal::rejected;
  // The new edge ab may exist already between two boundary vertices (a
  // spike folded against the two tets): the flip would double it.
  if (mesh.vertex_class(a) != VertexClass::interior && mesh.vertex_class(b) != VertexClass::interior &&
      tet_with_edge(mesh, a, b, s.ball) != kNoId)
    return Refusal::rejected;
  const std::array<TetId, 2> old{t, nb.tet()};
  const Acceptance<S, Criterion> accept(o.shape_floor);
  s.best_scores.clear();
  if constexpr (ScoredCriterion<Criterion>) {
    const double bar = accept.replacing(mesh, old).bar();
    for (std::size_t c = 0; c < 3; ++c) {
      s.best_scores.emplace_back(Criterion::template tet_score<S>(mesh, s.candidate[c]));
      if (s.best_scores.back() <= bar) return Refusal::rejected;
    }
  } else {
    s.old_tets.clear();
    s.old_tets.emplace_back(mesh.tet(t));
    s.old_tets.emplace_back(mesh.tet(nb.tet()));
    if (!Criterion::template prefers<S>(mesh, view(s.old_tets), view(s.candidate))) return Refusal::rejected;
  }
  if (!accept.keeps_shape(mesh, old, view(s.candidate))) return Refusal::rejected;
  if (!plan_cavity(mesh, old, view(s.candidate), s.plan)) return Refusal::rejected;
  return Flip23Plan{t, nb.tet(), face};
}

template <MetricSpace S, class Criterion>
void apply_flip23(Mesh& mesh, const Flip23Plan& plan, FlipScratch& s) {
  const std::array<TetId, 2> old{plan.t, plan.other};
  apply_cavity(mesh, old, view(s.candidate), s.plan, mesh.tet_ref(plan.t), s.created);
  Acceptance<S, Criterion>::after_apply(mesh, view(s.created), view(s.best_scores));
}

inline void preview_tets(const Mesh& mesh, std::span<const TetVertices> tets, PlannedTets& out) {
  out.clear();
  for (const auto& t : tets) out.push_back({t, detail::tet_points(mesh, t)});
}

// The seed of an operation on an edge: its two ends, held before the
// shell is walked (the edge removal, the boundary swap).
inline Found hold_edge_ends(const EdgeSeed& e, VertexList& hold) {
  const auto [a, b] = e.ends();
  hold.emplace_back(a);
  hold.emplace_back(b);
  return Found::cavity;
}

// The seed and find steps of an operation on an edge's shell (the boundary
// swap, the interface flip): the edge's ends held, then its shell walked
// from a's ball and its vertices held. The Scratch has `ball` and `shell`.
struct EdgeShellSteps {
  template <class Scratch>
  Found seed(const Mesh&, const EdgeSeed& e, Scratch&, VertexList& hold) const {
    return hold_edge_ends(e, hold);
  }
  template <class Scratch>
  Found find(const Mesh& mesh, const EdgeSeed& e, Scratch& s, VertexList& hold) const {
    const auto [a, b] = e.ends();
    if (!find_edge_shell(mesh, a, b, s.ball, s.shell)) return Found::gone;
    append_shell_vertices(mesh, a, b, s.shell, hold);
    return Found::cavity;
  }
};

// The edge removal as an operation: items are edges with a tet that held
// them when the work list was made (the shell walk starts there when the
// tet still holds the edge, else from a's ball).
template <MetricSpace S, class Criterion, Geometry G = ModelOrFacets>
struct EdgeRemoval {
  using Item = EdgeSeed;
  using Scratch = FlipScratch;
  using Plan = EdgeRemovalPlan;
  static constexpr std::string_view name = "edge-removal";
  FlipOptions options;
  G geometry{};

  // An edge removal of n tets makes 2n - 4, but few tries are applied
  // (1-5%): room for a net 0.05 tets per item, more between rounds.
  PassRoom room() const { return {.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 0.05}; }
  Found seed(const Mesh&, const Item& e, Scratch&, VertexList& hold) const { return hold_edge_ends(e, hold); }
  Found find(const Mesh& mesh, const Item& e, Scratch& s, VertexList& hold) const {
    const auto [a, b] = e.ends();
    // Holding a, a tet that shows a and b holds them for good (a writer
    // would hold a), so its peeked vertices are its vertices.
    const TetVertices held = mesh.peek_tet(e.tet);
    TetId start = e.tet;
    if (local_index(held, a) < 0 || local_index(held, b) < 0) {
      start = tet_with_edge(mesh, a, b, s.ball);
      if (start == kNoId) return Found::gone;
    }
    edge_shell_from(mesh, a, b, start, s.shell);
    append_shell_vertices(mesh, a, b, s.shell, hold);
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, const Item& e, Scratch& s) const {
    const auto [a, b] = e.ends();
    return decide_edge_removal<S, Criterion>(mesh, a, b, s, options, geometry);
  }
  void apply(Mesh& mesh, const Item&, const Plan& plan, Scratch& s) const {
    apply_edge_removal<S, Criterion>(mesh, plan, s);
  }
  void preview(const Mesh& mesh, const Item&, const Plan&, const Scratch& s, PlannedTets& out) const {
    preview_tets(mesh, view(s.best), out);
  }
};

struct FaceFlipScratch : FlipScratch {
  TetVertices seen{};  // the tet as the seed step read it
};

// The 2-3 flip as an operation: an item is a tet, whose faces are tried
// in order (those whose tets are both at or above face_flip_below are
// skipped) until one flips. It flips inner faces only: the Geometry is
// held like every operation's, and never asked.
template <MetricSpace S, class Criterion, Geometry G = ModelOrFacets>
struct FaceFlip {
  using Item = TetId;
  using Scratch = FaceFlipScratch;
  using Plan = Flip23Plan;
  static constexpr std::string_view name = "flip23";
  FlipOptions options;
  double face_flip_below = 1.0;
  G geometry{};

  PassRoom room() const { return {.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 0.05}; }
  Found seed(const Mesh& mesh, TetId t, Scratch& s, VertexList& hold) const {
    s.seen = mesh.peek_tet(t);
    for (VertexId v : s.seen)
      if (v == kNoId) return Found::gone;
    hold.insert(hold.end(), s.seen.begin(), s.seen.end());
    return Found::cavity;
  }
  Found find(const Mesh& mesh, TetId t, Scratch& s, VertexList& hold) const {
    if (mesh.tet(t) != s.seen) return Found::gone;  // changed since the list was made
    for (int f = 0; f < 4; ++f) {
      const FaceRef nb = mesh.neighbour(t, f);
      if (nb.valid()) hold.emplace_back(mesh.tet(nb.tet())[nb.face()]);
    }
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, TetId t, Scratch& s) const {
    const bool t_below = face_flip_below >= 1.0 || cached_mean_ratio<S>(mesh, t) < face_flip_below;
    int tries = 0;
    bool rejected = false;
    for (int f = 0; f < 4; ++f) {
      const FaceRef nb = mesh.neighbour(t, f);
      if (!nb.valid()) continue;
      if (!t_below && cached_mean_ratio<S>(mesh, nb.tet()) >= face_flip_below) continue;
      ++tries;
      const auto d = decide_flip23<S, Criterion>(mesh, t, f, s, options);
      if (d) return {d.plan(), tries};
      rejected = rejected || d.why() == Refusal::rejected;
    }
    return {rejected ? Refusal::rejected : Refusal::not_applicable, tries};
  }
  void apply(Mesh& mesh, TetId, const Plan& plan, Scratch& s) const { apply_flip23<S, Criterion>(mesh, plan, s); }
  void preview(const Mesh& mesh, TetId, const Plan&, const Scratch& s, PlannedTets& out) const {
    preview_tets(mesh, view(s.candidate), out);
  }
};

}  // namespace metrica
