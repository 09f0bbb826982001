// The 2-2 flip of an internal surface, made on its two sides together.
// Surface edge ab (not a ridge) has a closed shell that the surface's two
// faces through ab, abc and abd, cut into two half-shells, one on each
// side (ring c .. d on each). The flip makes cd the surface's edge: each
// half-shell becomes a fan of its ring polygon, closed by cd, joined to a
// and to b (the edge removal of flips.hpp, side by side), so acd and bcd
// are the new surface faces between the two sides, and every new tet keeps
// its side's region. The outer boundary's 2-2 flip is the edge removal of
// an open shell (flips.hpp); across an internal surface no flip may reach,
// so without this one the surface's triangles keep the shape the splits
// gave them, and so do the tets standing on them.
//
// Decided when the worst new tet (mean ratio) beats the shell's worst, the
// new facets fit the Geometry (on a model, its normal; without one a, b,
// c, d coplanar to round-off, so the regions keep their volumes and the
// surface its place), every new tet is positive (Precision), and cd is not
// an edge yet. A half-shell of one tet (a sliver in a fold of the surface)
// is the interface swap's (interface_swap.hpp). Never on required edges
// or a kept surface.
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/cavity.hpp>
#include <metrica/operators/flips.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/operators/work_list.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace metrica {

struct InterfaceFlipOptions {
  // Largest half-shell tried, in tets (its ring has one vertex more).
  int max_half = 4;
  // The new facets' largest normal deviation from the old (1 - |cos|);
  // CadGeometry also allows its own bound and the old facets' deviation.
  double max_normal_deviation = 1e-9;
  // The worst new tet must beat the shell's worst by this share.
  double gain = 1e-3;
};

struct InterfaceFlipScratch : ScratchGeneration {
  TetList ball;
  Shell shell;
  VertexList ring, polygon;
  NewTets candidate, best;                            // best: both sides' fans
  boost::container::small_vector<int, 32> refs;       // of best
  boost::container::small_vector<double, 32> scores;  // of best, mean ratios
  CavityPlan plan;
  TetList created;
};

struct InterfaceFlipPlan {
  VertexId a = kNoId, b = kNoId;
  SurfaceId surface = 0;
};

template <MetricSpace S, Geometry G>
struct InterfaceFlip : EdgeShellSteps {
  using Item = EdgeSeed;
  using Scratch = InterfaceFlipScratch;
  using Plan = InterfaceFlipPlan;
  static constexpr std::string_view name = "interface-flip";
  InterfaceFlipOptions options;
  G geometry{};

  PassRoom room() const { return {.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 2}; }

  Decision<Plan> decide(const Mesh& mesh, const Item& e, Scratch& s) const {
    const auto [a, b] = e.ends();
    const Shell& shell = s.shell;
    const std::size_t n = shell.tets.size();
    if (!shell.closed || mesh.keeps_surface() || mesh.is_ridge(a, b) || mesh.is_required_edge(a, b))
      return Refusal::not_applicable;
    // Tet k of the shell is (a, b, ring[k], ring[k+1]); the face it shares
    // with tet k - 1 is (a, b, ring[k]). The surface's two: at i < j.
    const int sign = edge_ring(mesh, a, b, shell, s.ring);
    std::array<std::size_t, 2> at{};
    int on = 0;
    SurfaceId surface = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const TetId t = shell.tets[k];
      const SurfaceId id = mesh.internal_surface_id(t, local_index(mesh.tet(t), s.ring[(k + 1) % n]));
      if (id == 0) continue;
      if (on == 2 || (surface != 0 && id != surface)) return Refusal::not_applicable;
      surface = id;
      at[static_cast<std::size_t>(on++)] = k;
    }
    if (on != 2) return Refusal::not_applicable;
    std::sort(at.begin(), at.end());
    const VertexId c = s.ring[at[0]], d = s.ring[at[1]];
    // Each side: the best fan of its polygon (ring from one surface face
    // to the other), by its worst tet.
    s.best.clear();
    s.refs.clear();
    s.scores.clear();
    double worst_new = 1.0;
    for (int side = 0; side < 2; ++side) {
      const std::size_t from = at[static_cast<std::size_t>(side)];
      const std::size_t count = side == 0 ? at[1] - at[0] : n - at[1] + at[0];
      if (count < 2 || static_cast<int>(count) > options.max_half) return Refusal::not_applicable;
      s.polygon.clear();
      for (std::size_t k = 0; k <= count; ++k) s.polygon.emplace_back(s.ring[(from + k) % n]);
      const int region = mesh.tet_ref(shell.tets[from]);
      const std::size_t m = s.polygon.size();
      const std::size_t fans = m == 3 ? 1 : m == 4 ? 2 : m;
      double side_best = 0.0;
      std::size_t first = s.best.size();
      for (std::size_t k = 0; k < fans; ++k) {
        fan_tets(s.polygon, k, a, b, sign, s.candidate);
        if (!all_positive(mesh, view(s.candidate))) continue;
        double q = 1.0;
        for (const auto& t : s.candidate) q = std::min(q, S::mean_ratio(mesh, t));
        if (q <= side_best) continue;
        side_best = q;
        s.best.resize(first);
        s.refs.resize(first);
        s.scores.resize(first);
        for (const auto& t : s.candidate) {
          s.best.emplace_back(t);
          s.refs.emplace_back(region);
          s.scores.emplace_back(S::mean_ratio(mesh, t));
        }
      }
      if (side_best <= 0.0) return Refusal::rejected;
      worst_new = std::min(worst_new, side_best);
    }
    double worst_old = 1.0;
    for (TetId t : shell.tets) worst_old = std::min(worst_old, cached_mean_ratio<S>(mesh, t));
    if (!(worst_new > worst_old * (1.0 + options.gain))) return Refusal::rejected;
    // The new facets fit where the old ones were.
    const Point &pa = mesh.point(a), &pb = mesh.point(b), &pc = mesh.point(c), &pd = mesh.point(d);
    if (!geometry.places(mesh, a) && !in_plane(pa, pb, pc, pd)) return Refusal::rejected;
    const Eigen::Vector3d old_normal = face_normal(mesh, a, b, c);
    if (!geometry.facet_fits(mesh, a, c, d, surface, old_normal, options.max_normal_deviation) ||
        !geometry.facet_fits(mesh, b, c, d, surface, face_normal(mesh, a, b, d), options.max_normal_deviation))
      return Refusal::rejected;
    // cd is new (else the flip would double an edge).
    if (tet_with_edge(mesh, c, d, s.ball) != kNoId) return Refusal::rejected;
    const std::array<CavityPlan::InnerSurfaceFace, 2> faces{
        CavityPlan::InnerSurfaceFace{sorted(TriangleVertices{a, c, d}), surface},
        CavityPlan::InnerSurfaceFace{sorted(TriangleVertices{b, c, d}), surface}};
    if (!plan_cavity(mesh, view(shell.tets), view(s.best), s.plan, kNoId, kNoId, 0, view(s.refs), faces))
      return Refusal::rejected;
    return Plan{a, b, surface};
  }

  void apply(Mesh& mesh, const Item&, const Plan&, Scratch& s) const {
    apply_cavity(mesh, view(s.shell.tets), view(s.best), s.plan, 0, s.created, view(s.refs));
    for (std::size_t i = 0; i < s.created.size(); ++i) mesh.cache_quality(s.created[i], s.scores[i]);
  }
  void preview(const Mesh& mesh, const Item&, const Plan&, const Scratch& s, PlannedTets& out) const {
    preview_tets(mesh, view(s.best), out);
  }
};

// The edges of internal surfaces off ridges, each once with a tet that
// holds it.
inline std::vector<EdgeSeed> interface_edge_seeds(const Mesh& mesh) {
  std::vector<EdgeSeed> out;
  if (!mesh.has_internal_surfaces()) return out;
  for_each_surface_face(mesh, [&](TetId t, int f) {
    if (!mesh.neighbour(t, f).valid()) return;
    const auto tri = face_vertices(mesh.tet(t), f);
    for (int i = 0; i < 3; ++i) {
      const VertexId a = tri[i], b = tri[(i + 1) % 3];
      if (!mesh.is_ridge(a, b)) out.push_back({edge_key(a, b), t});
    }
  });
  std::sort(out.begin(), out.end(), [](const EdgeSeed& x, const EdgeSeed& y) { return x.key() < y.key(); });
  out.erase(
      std::unique(out.begin(), out.end(), [](const EdgeSeed& x, const EdgeSeed& y) { return x.key() == y.key(); }),
      out.end());
  return out;
}

// The pass: every edge of an internal surface whose flip lifts its shell.
template <MetricSpace S, Concurrency C, Geometry G>
OperatorStats flip_interfaces(Mesh& mesh, const InterfaceFlipOptions& o, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  const std::vector<EdgeSeed> edges = interface_edge_seeds(mesh);
  if (!edges.empty()) stats = run_pass<C>(mesh, InterfaceFlip<S, G>{{}, o, geometry}, edges);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
