// The boundary 2-2 flip for the model: boundary edge ab, whose two
// boundary faces (a b v0, a b v2) lie on one surface and whose shell is
// the two tets around ring v0 v1 v2, becomes the edge v0 v2 when the new
// facets follow the model better: their largest deviation from it
// (Geometry::facet_deviation, 1 - |cos| of the facet's and the model's
// normals at the facet's centroid) is at most half the old facets'. The
// new tets must be positive (Precision) and keep their shape (no new tet
// below the floor unless the old ones were worse). Off a model
// (NoGeometry, ModelOrFacets without one) nothing deviates and nothing is
// swapped.
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/cavity.hpp>
#include <metrica/operators/flips.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/work_list.hpp>

#include <algorithm>
#include <vector>

namespace metrica {

struct BoundarySwapOptions {
  // The new facets' deviation must be at most this share of the old.
  double gain = 0.5;
  double shape_floor = ShapeFloors::boundary_swap;
  // Old facets that deviate less than this are left as they are.
  double below = 1e-4;
};

template <MetricSpace S, Geometry G>
struct BoundarySwap : EdgeShellSteps {
  using Item = EdgeSeed;
  using Scratch = FlipScratch;
  using Plan = EdgeRemovalPlan;
  static constexpr std::string_view name = "boundary-swap";
  BoundarySwapOptions options;
  G geometry{};

  PassRoom room() const { return {.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 0.05}; }
  Decision<Plan> decide(const Mesh& mesh, const Item& e, Scratch& s) const {
    const auto [a, b] = e.ends();
    const Shell& shell = s.shell;
    if (shell.closed || shell.tets.size() != 2 || mesh.is_ridge(a, b) || mesh.keeps_surface() ||
        mesh.is_required_edge(a, b))
      return Refusal::not_applicable;
    const int ref = mesh.tet_ref(shell.tets[0]);
    if (mesh.tet_ref(shell.tets[1]) != ref) return Refusal::not_applicable;
    SurfaceId surface = 0;
    int faces = 0;
    for (TetId t : shell.tets)
      for (int f = 0; f < 4; ++f) {
        const VertexId opp = mesh.tet(t)[f];
        if (opp == a || opp == b || mesh.neighbour(t, f).valid()) continue;
        if (faces == 0) surface = mesh.surface_id(t, f);
        if (mesh.surface_id(t, f) != surface) return Refusal::not_applicable;
        ++faces;
      }
    if (faces != 2 || surface <= 0) return Refusal::not_applicable;
    const int sign = edge_ring(mesh, a, b, shell, s.ring);
    if (s.ring.size() != 3) return Refusal::not_applicable;
    const VertexId v0 = s.ring.front(), v2 = s.ring.back();
    const double before =
        std::max(geometry.facet_deviation(mesh, a, b, v0, surface), geometry.facet_deviation(mesh, a, b, v2, surface));
    if (before < options.below) return Refusal::not_applicable;
    const double after = std::max(geometry.facet_deviation(mesh, v0, v2, a, surface),
                                  geometry.facet_deviation(mesh, v0, v2, b, surface));
    if (after > options.gain * before) return Refusal::rejected;
    fan_tets(s.ring, 0, a, b, sign, s.candidate);
    if (!all_positive(mesh, view(s.candidate))) return Refusal::rejected;
    if (!Acceptance<S, ShapeOnly>(options.shape_floor).keeps_shape(mesh, view(shell.tets), view(s.candidate)))
      return Refusal::rejected;
    // The new boundary edge must not exist already.
    if (tet_with_edge(mesh, v0, v2, s.ball) != kNoId) return Refusal::rejected;
    s.best = s.candidate;
    s.best_scores.clear();
    if (!plan_cavity(mesh, view(shell.tets), view(s.best), s.plan, kNoId, kNoId, surface)) return Refusal::rejected;
    return EdgeRemovalPlan{a, b, ref};
  }
  void apply(Mesh& mesh, const Item&, const Plan& plan, Scratch& s) const {
    apply_cavity(mesh, view(s.shell.tets), view(s.best), s.plan, plan.ref, s.created);
  }
  void preview(const Mesh& mesh, const Item&, const Plan&, const Scratch& s, PlannedTets& out) const {
    preview_tets(mesh, view(s.best), out);
  }
};

// The boundary edges off ridges, each with a tet that holds it.
inline std::vector<EdgeSeed> boundary_edge_seeds(const Mesh& mesh) {
  std::vector<EdgeSeed> out;
  for_each_boundary_face(mesh, [&](TetId t, int f) {
    const auto tri = face_vertices(mesh.tet(t), f);
    for (int i = 0; i < 3; ++i) {
      const VertexId a = tri[i], b = tri[(i + 1) % 3];
      if (a < b && !mesh.is_ridge(a, b)) out.push_back({edge_key(a, b), t});
    }
  });
  // Each inner boundary edge is seen from its two faces, once as a < b.
  std::sort(out.begin(), out.end(), [](const EdgeSeed& x, const EdgeSeed& y) { return x.key() < y.key(); });
  return out;
}

// The pass: every boundary edge whose facets deviate from the model.
template <MetricSpace S, Concurrency C, Geometry G>
OperatorStats swap_toward_model(Mesh& mesh, const BoundarySwapOptions& o, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  const std::vector<EdgeSeed> edges = boundary_edge_seeds(mesh);
  stats = run_pass<C>(mesh, BoundarySwap<S, G>{{}, o, geometry}, edges);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
