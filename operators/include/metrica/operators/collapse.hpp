// Edge collapse (seed, section 3.3): a short edge ab disappears by merging
// a into b. The ball of a is the cavity; its tets that hold b vanish and
// the others have a renamed b (cavity.hpp with renaming).
//
// Rules that keep the boundary what it was (decide, before any write):
//   - a corner or a required vertex never moves;
//   - a ridge vertex moves only along a ridge edge (b on its ridge);
//   - a surface vertex moves only along an edge of its surface (b on it:
//     an outer surface, or the internal surface it lies on), and the
//     surface faces it drags fit the Geometry (NoGeometry: they keep their
//     plane, normal deviation below a tolerance, so the volume is
//     conserved; an internal surface's exactly, so that it stays on the
//     input's triangles; CadGeometry: they follow the model's normal);
//   - the outer boundary and each internal surface stay manifold (no
//     edge of them gets a third face) and the regions on an internal
//     surface's two sides stay apart;
//   - every new tet is positively oriented (Precision), no new edge is
//     longer than max_new_length, and the worst new tet is above the
//     quality floor or no worse than the worst tet of the old ball;
//   - the faces still match one to one (plan_cavity: the link condition).
// When neither end may take the other's place without making long edges,
// two interior ends merge at the edge's metric midpoint instead.
#pragma once

#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/boundary_placement.hpp>
#include <metrica/operators/cavity.hpp>
#include <metrica/operators/edge_queue.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/pass_scope.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/operators/volume_budget.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace metrica {

struct CollapseOptions {
  // Edges shorter than this (metric length) are collapsed.
  double min_length = kUnitBand.lo;
  // A collapse may not create an edge longer than this. Above the split
  // threshold the two operators undo a little of each other's work, but
  // more short edges go (UGAWG linear: 92.6% of edges in range against
  // 91.0% with sqrt 2).
  double max_new_length = 1.5;
  double shape_floor = ShapeFloors::collapse;
  // Largest 1 - cos between a boundary face's normal before and after.
  double max_normal_deviation = 1.0 - std::cos(2.0 * std::numbers::pi / 180.0);
  // When set, a collapse that moves the boundary takes its exact change of
  // the domain's volume from this budget, and is refused when the budget
  // cannot give it (volume_budget.hpp; the adapter sets it off a model).
  const VolumeBudget* volume_budget = nullptr;
  // When set, a collapse must raise the worst tet of the ball (both balls
  // for a merge at the midpoint): the repair rounds collapse edges of any
  // length at a poor tet, and only to lift it.
  bool require_gain = false;
  // The metric of a vertex merged at an edge's midpoint; only edges with
  // an end whose ball changed since scope.changed_since (a collapse reads
  // the two balls only); the list from scope.known where it can.
  PassScope scope{};
};

struct CollapseScratch : ScratchGeneration {
  TetList ball, ball_b;
  Shell shell;
  VertexList neighbours, neighbours_b;  // of a, of b
  NewTets old_tets, new_tets, dragged;
  boost::container::small_vector<double, 32> new_quality;  // of new_tets
  CavityPlan plan;
  TetList created;
  boost::container::small_vector<int, 32> new_refs;  // of new_tets, when the ball spans regions
  boost::container::small_vector<std::pair<TriangleVertices, SurfaceId>, 32> around;  // surface_link_kept
  VertexList joined, faced;                                                           // boundary_link_kept
};

// May vertex a move onto b by the class rules? `shell` is ab's.
inline bool collapse_allowed(const Mesh& mesh, VertexId a, VertexId b, const Shell& shell) {
  if (mesh.is_fixed(a)) return false;
  switch (mesh.vertex_class(a)) {
    case VertexClass::corner: return false;
    case VertexClass::ridge: return mesh.is_ridge(a, b);
    case VertexClass::surface:
      // On one surface: an outer one (ab on the boundary, an open shell)
      // or an internal one (ab on it).
      return mesh.on_internal_surface(a) ? shell.closed && edge_surface(mesh, shell, a, b) != 0 : !shell.closed;
    case VertexClass::interior: return true;
  }
  return false;
}

// Does an internal surface stay manifold when a merges into b? Its faces
// through a, renamed, join those through b (the two on ab vanish): no
// edge from b may then hold three faces of one surface (the surface's
// link condition). s.ball and s.ball_b are the two balls.
inline bool surface_link_kept(const Mesh& mesh, VertexId a, VertexId b, CollapseScratch& s) {
  auto holds = [](const TriangleVertices& f, VertexId v) { return std::find(f.begin(), f.end(), v) != f.end(); };
  s.around.clear();
  for (const auto* ball : {&s.ball, &s.ball_b}) {
    const VertexId v = ball == &s.ball ? a : b;
    for (TetId t : *ball) {
      const auto& tv = mesh.tet(t);
      for (int f = 0; f < 4; ++f) {
        const FaceRef n = mesh.neighbour(t, f);
        const SurfaceId id = mesh.internal_surface_id(t, f);
        if (tv[f] == v || !n.valid() || id == 0 || n.tet() < t) continue;  // each face once
        TriangleVertices key = face_vertices(tv, f);
        if (holds(key, a) && holds(key, b)) continue;  // on ab: vanishes
        for (auto& x : key)
          if (x == a) x = b;
        s.around.emplace_back(sorted(key), id);
      }
    }
  }
  for (const auto& [key, id] : s.around)
    for (VertexId w : key) {
      if (w == b) continue;
      int faces = 0;
      for (const auto& [other, other_id] : s.around) faces += other_id == id && holds(other, w);
      if (faces > 2) return false;
    }
  return true;
}

// Does the outer boundary stay manifold when a merges into b? A vertex x
// joined to a and to b by boundary edges must make a boundary face with
// them: when abx is a face inside the mesh (a tet whose four vertices lie
// on the boundary, three of its faces on it), edge bx would end on four
// boundary faces. s.ball and s.ball_b are the two balls.
inline bool boundary_link_kept(const Mesh& mesh, VertexId a, VertexId b, CollapseScratch& s) {
  auto holds = [](const auto& list, VertexId v) { return std::find(list.begin(), list.end(), v) != list.end(); };
  s.joined.clear();
  s.faced.clear();
  for (TetId t : s.ball) {
    const auto& tv = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      if (tv[f] == a || mesh.neighbour(t, f).valid()) continue;
      const auto fv = face_vertices(tv, f);
      VertexList& to = holds(fv, b) ? s.faced : s.joined;
      for (VertexId x : fv)
        if (x != a && x != b) to.emplace_back(x);
    }
  }
  if (s.joined.empty()) return true;
  for (TetId t : s.ball_b) {
    const auto& tv = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      if (tv[f] == b || mesh.neighbour(t, f).valid()) continue;
      const auto fv = face_vertices(tv, f);
      if (holds(fv, a)) continue;
      for (VertexId x : fv)
        if (x != b && holds(s.joined, x) && !holds(s.faced, x)) return false;
    }
  }
  return true;
}

struct CollapsePlan {
  VertexId from = kNoId, to = kNoId;
  bool moved = false;  // `to` moves to `at` with metric `metric`
  Point at = Point::Zero();
  VertexMetric metric;
};

// Decide the collapse of a onto b, with b left where it is or, when
// `moved` is given (both ends interior), moved to that point with metric
// `moved_metric` (the merge at the edge's metric midpoint, which makes
// shorter edges than either end). s.ball, s.ball_b, s.neighbours and
// s.neighbours_b hold the two balls and the vertices joined to each end
// (the caller holds them).
template <MetricSpace S, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
Decision<CollapsePlan> decide_collapse(const Mesh& mesh, VertexId a, VertexId b, CollapseScratch& s,
                                       const CollapseOptions& o, const Point* moved = nullptr,
                                       const VertexMetric* moved_metric = nullptr, const G& geometry = {}) {
  if (!edge_shell(mesh, a, b, s.ball, s.shell)) return Refusal::not_applicable;
  if (!collapse_allowed(mesh, a, b, s.shell)) return Refusal::not_applicable;
  // The link condition on edges: a vertex joined to both a and b must be
  // on a tet of ab, else edge bx would end up in two fans of tets (a
  // pinched edge; on the boundary, an edge of four boundary faces).
  for (VertexId x : s.neighbours) {
    if (x == b || std::find(s.neighbours_b.begin(), s.neighbours_b.end(), x) == s.neighbours_b.end()) continue;
    bool on_shell = false;
    for (TetId t : s.shell.tets) on_shell = on_shell || local_index(mesh.tet(t), x) >= 0;
    if (!on_shell) return Refusal::not_applicable;
  }
  if (mesh.vertex_class(a) != VertexClass::interior && !boundary_link_kept(mesh, a, b, s))
    return Refusal::not_applicable;
  if (moved != nullptr && (mesh.vertex_class(b) != VertexClass::interior || mesh.is_fixed(b)))
    return Refusal::not_applicable;
  // A vertex between regions (on an internal surface) has a ball in
  // several: each new tet keeps its old tet's.
  const int ref = mesh.tet_ref(s.ball[0]);
  bool regions = false;
  s.old_tets.clear();
  s.new_tets.clear();
  s.new_refs.clear();
  for (TetId t : s.ball) {
    regions = regions || mesh.tet_ref(t) != ref;
    TetVertices v = mesh.tet(t);
    s.old_tets.emplace_back(v);
    if (local_index(v, b) >= 0) continue;
    v[local_index(v, a)] = b;
    s.new_tets.emplace_back(v);
  }
  if (regions)
    for (TetId t : s.ball)
      if (local_index(mesh.tet(t), b) < 0) s.new_refs.emplace_back(mesh.tet_ref(t));
  if (mesh.on_internal_surface(a) && !surface_link_kept(mesh, a, b, s)) return Refusal::rejected;
  // The tets of b's ball that b's move drags along (it keeps their topology).
  s.dragged.clear();
  if (moved != nullptr)
    for (TetId t : s.ball_b)
      if (local_index(mesh.tet(t), a) < 0) s.dragged.emplace_back(mesh.tet(t));
  const Point pb = moved != nullptr ? *moved : mesh.point(b);
  const Sym6 mb = moved_metric != nullptr ? moved_metric->m : S::vertex_metric(mesh, b);
  // The checks run cheapest first; the mean ratios (a tensor exponential
  // each in the log-Euclidean space) come last.
  for (const auto* list : {&s.new_tets, &s.dragged})
    for (const auto& t : *list) {
      const TetPoints x = tet_points_moved(mesh, t, b, pb);
      if (!positive_tet(x[0], x[1], x[2], x[3])) return Refusal::rejected;
    }
  // New edges: b to a's neighbours; when b moves, all of b's edges too.
  const UnitBand allowed{0.0, o.max_new_length};
  for (const auto* list : {&s.neighbours, &s.neighbours_b}) {
    if (list == &s.neighbours_b && moved == nullptr) break;
    for (VertexId x : *list)
      if (x != a && x != b && !ugawg_length_in(allowed, mesh.point(x) - pb, mb, S::vertex_metric(mesh, x)))
        return Refusal::rejected;
  }
  if (mesh.vertex_class(a) != VertexClass::interior) {
    // Surface faces through a (and not b) keep their side and fit the
    // Geometry; off a model, an internal surface's keep their plane
    // exactly (b in the plane of the face it replaces a in).
    const bool interface = mesh.on_internal_surface(a);
    for (TetId t : s.ball) {
      const auto& v = mesh.tet(t);
      if (local_index(v, b) >= 0) continue;
      for (int f = 0; f < 4; ++f) {
        const bool internal = mesh.neighbour(t, f).valid();
        if (v[f] == a || (internal && (!interface || mesh.internal_surface_id(t, f) == 0))) continue;
        auto fv = face_vertices(v, f);
        const Eigen::Vector3d before = face_normal(mesh, fv[0], fv[1], fv[2]);
        if (internal && !geometry.places(mesh, a) &&
            !in_plane(mesh.point(fv[0]), mesh.point(fv[1]), mesh.point(fv[2]), mesh.point(b)))
          return Refusal::rejected;
        for (auto& x : fv)
          if (x == a) x = b;
        if (before.dot(face_normal(mesh, fv[0], fv[1], fv[2])) <= 0.0 ||
            !geometry.facet_fits(mesh, fv[0], fv[1], fv[2], mesh.face_surface_id(t, f), before, o.max_normal_deviation))
          return Refusal::rejected;
      }
    }
  }
  if (!plan_cavity(mesh, view(s.ball), view(s.new_tets), s.plan, a, b, 0, view(s.new_refs))) return Refusal::rejected;
  // Accepted when every new tet passes the shape floor and beats the old
  // ball (both balls when b moves) under the criterion; with
  // require_gain, refused unless every new tet beats the worst old in
  // mean ratio. The mean ratios are kept for the quality cache.
  auto r = Acceptance<S, Criterion>(o.shape_floor)
               .replacing(mesh, view(s.ball), moved != nullptr ? view(s.ball_b) : std::span<const TetId>{});
  s.new_quality.clear();
  for (const auto* list : {&s.new_tets, &s.dragged})
    for (const auto& t : *list) {
      const TetPoints x = tet_points_moved(mesh, t, b, pb);
      const double q = S::mean_ratio(mesh, t, x);
      if (list == &s.new_tets) s.new_quality.emplace_back(q);
      if (o.require_gain && q <= r.worst_old()) return Refusal::rejected;
      if (!r.shape_admits(q) || !r.beats(t, x)) return Refusal::rejected;
    }
  // Last, once nothing else refuses: the change of volume of a boundary
  // collapse (the new tets against the old ball) from the budget.
  if (o.volume_budget != nullptr && mesh.vertex_class(a) != VertexClass::interior) {
    double delta = 0.0;
    for (TetId t : s.ball) {
      const auto& v = mesh.tet(t);
      delta -= tet_volume(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]));
    }
    for (const auto& v : s.new_tets)
      delta += tet_volume(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]));
    if (!o.volume_budget->take(delta)) return Refusal::rejected;
  }
  CollapsePlan plan{a, b, moved != nullptr, pb, {}};
  if (moved_metric != nullptr) plan.metric = *moved_metric;
  return plan;
}

// Apply a decided collapse (the scratch as decide_collapse left it).
inline void apply_collapse(Mesh& mesh, const CollapsePlan& plan, CollapseScratch& s) {
  apply_cavity(mesh, view(s.ball), view(s.new_tets), s.plan, mesh.tet_ref(s.ball[0]), s.created, view(s.new_refs));
  // The new tets' mean ratios, measured at their final points in their
  // final metric, go to the quality cache (not when b moves: its metric
  // changes below).
  if (!plan.moved)
    for (std::size_t i = 0; i < s.created.size(); ++i) mesh.cache_quality(s.created[i], s.new_quality[i]);
  mesh.merge_edge_tags(plan.from, plan.to, view(s.neighbours));
  mesh.remove_vertex(plan.from);
  if (plan.moved) {
    mesh.point(plan.to) = plan.at;
    set_vertex_metric(mesh, plan.to, plan.metric);
    for (TetId t : s.ball_b)
      if (mesh.tet_alive(t)) mesh.touch_tet(t);  // dragged along
  }
}

// The collapse of a short edge as an operation: it tries to remove the
// end of lower class (interior before surface before ridge), then the
// other, then (two interior ends) to merge them at the edge's metric
// midpoint.
template <MetricSpace S, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
struct Collapse {
  using Item = EdgeCandidate;
  using Scratch = CollapseScratch;
  using Plan = CollapsePlan;
  static constexpr std::string_view name = "collapse";
  CollapseOptions options;
  G geometry{};

  // A collapse frees tets (net); a thread reuses its own at once.
  PassRoom room() const { return {.vertices_per_item = 0, .tets_per_item = 0}; }
  Found seed(const Mesh&, const Item& c, Scratch&, VertexList& hold) const {
    hold.emplace_back(c.a);
    hold.emplace_back(c.b);
    return Found::cavity;
  }
  // Both balls: the endpoint collapses change ball(from), the merge at the
  // midpoint moves b too. The cavity is the union of the two neighbour
  // lists (each holds the other end).
  Found find(const Mesh& mesh, const Item& c, Scratch& s, VertexList& hold) const {
    vertex_ball(mesh, c.a, s.ball);
    vertex_neighbours(mesh, s.ball, c.a, s.neighbours);
    if (std::find(s.neighbours.begin(), s.neighbours.end(), c.b) == s.neighbours.end()) return Found::gone;
    vertex_ball(mesh, c.b, s.ball_b);
    vertex_neighbours(mesh, s.ball_b, c.b, s.neighbours_b);
    hold = s.neighbours;
    append_new(s.neighbours_b, hold);
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, const Item& c, Scratch& s) const {
    VertexId from = c.a, to = c.b;
    if (mesh.vertex_class(to) < mesh.vertex_class(from)) std::swap(from, to);
    // The balls found for locking serve every attempt (the attempts that
    // fail write nothing); s.ball is always the ball of `from`.
    if (from != c.a) {
      std::swap(s.ball, s.ball_b);
      std::swap(s.neighbours, s.neighbours_b);
    }
    bool rejected = false;
    for (int attempt = 0; attempt < 3; ++attempt) {
      if (attempt == 1) {
        std::swap(from, to);
        std::swap(s.ball, s.ball_b);
        std::swap(s.neighbours, s.neighbours_b);
      }
      Decision<Plan> d = Refusal::not_applicable;
      if (attempt < 2) {
        d = decide_collapse<S, Criterion>(mesh, from, to, s, options, nullptr, nullptr, geometry);
      } else {
        if (mesh.vertex_class(from) != VertexClass::interior || mesh.vertex_class(to) != VertexClass::interior) break;
        const auto& ma = S::vertex_metric(mesh, from);
        const auto& mb = S::vertex_metric(mesh, to);
        const Eigen::Vector3d e = mesh.point(to) - mesh.point(from);
        const double t = metric_midpoint(std::sqrt(metric_norm2(ma, e)), std::sqrt(metric_norm2(mb, e)));
        const Point p = mesh.point(from) + t * e;
        const std::array<VertexId, 2> ends{from, to};
        const std::array<double, 2> w{1.0 - t, t};
        const VertexMetric m = new_vertex_metric<S>(mesh, options.scope.metric, ends, w, p);
        d = decide_collapse<S, Criterion>(mesh, from, to, s, options, &p, &m, geometry);
      }
      if (d) return d;
      rejected = rejected || d.why() == Refusal::rejected;
    }
    return rejected ? Refusal::rejected : Refusal::not_applicable;
  }
  void apply(Mesh& mesh, const Item&, const Plan& plan, Scratch& s) const { apply_collapse(mesh, plan, s); }
  void preview(const Mesh& mesh, const Item&, const Plan& plan, const Scratch& s, PlannedTets& out) const {
    out.clear();
    for (const auto* list : {&s.new_tets, &s.dragged})
      for (const auto& t : *list) {
        out.push_back({t, tet_points_moved(mesh, t, plan.to, plan.at)});
      }
  }
};

// The collapse pass: edges shorter than min_length, shortest first.
template <MetricSpace S, Concurrency C, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
OperatorStats collapse_edges(Mesh& mesh, const CollapseOptions& o = {}, const G& geometry = {}) {
  Stopwatch clock;
  const auto todo =
      edges_beyond<S, C>(mesh, o.min_length, EdgeOrder::shortest_first, o.scope.changed_since, o.scope.known);
  OperatorStats stats = run_pass<C>(mesh, Collapse<S, Criterion, G>{o, geometry}, todo);
  stats.seconds = clock.seconds();
  return stats;
}

// A last resort, outside a pass: v collapses onto a neighbour u with
// onto(u) whose collapse the class rules, the Geometry and a positive ball
// allow, at any length. By default the first such u at any shape (the
// flips and smoothing that follow lift what it leaves); with `best`, the
// u whose worst new tet is best, each new tet at or above `shape_floor`
// unless it beats the ball's worst. Serial.
struct AnyCollapse {
  std::size_t weighed = 0;  // neighbours onto(u) admitted
  bool done = false;
};
struct AnyCollapseRule {
  double shape_floor = 0.0;
  bool best = false;
};
template <MetricSpace S, Geometry G, class Onto>
AnyCollapse collapse_onto_any_neighbour(Mesh& mesh, VertexId v, CollapseScratch& s, const G& geometry, Onto&& onto,
                                        AnyCollapseRule rule = {}) {
  CollapseOptions any;
  any.min_length = std::numeric_limits<double>::infinity();
  any.max_new_length = std::numeric_limits<double>::infinity();
  any.shape_floor = rule.shape_floor;
  AnyCollapse result;
  auto decide = [&](VertexId u) {
    vertex_ball(mesh, v, s.ball);
    vertex_neighbours(mesh, s.ball, v, s.neighbours);
    vertex_ball(mesh, u, s.ball_b);
    vertex_neighbours(mesh, s.ball_b, u, s.neighbours_b);
    return decide_collapse<S, ShapeOnly>(mesh, v, u, s, any, nullptr, nullptr, geometry);
  };
  vertex_ball(mesh, v, s.ball);
  vertex_neighbours(mesh, s.ball, v, s.neighbours);
  const VertexList around = s.neighbours;
  VertexId chosen = kNoId;
  double chosen_worst = -1.0;
  for (VertexId u : around) {
    if (!onto(u)) continue;
    ++result.weighed;
    const auto d = decide(u);
    if (!d) continue;
    if (!rule.best) {
      apply_collapse(mesh, d.plan(), s);
      result.done = true;
      return result;
    }
    const double worst = s.new_quality.empty() ? 1.0 : *std::min_element(s.new_quality.begin(), s.new_quality.end());
    if (worst > chosen_worst) {
      chosen = u;
      chosen_worst = worst;
    }
  }
  if (chosen == kNoId) return result;
  const auto d = decide(chosen);  // again: the scratch as its decision leaves it
  if (!d) return result;
  apply_collapse(mesh, d.plan(), s);
  result.done = true;
  return result;
}

}  // namespace metrica
