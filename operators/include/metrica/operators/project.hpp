// Projection onto the model: a boundary vertex off its entity's point
// (a placement that had to backtrack, boundary_placement.hpp) moves to
// that point when its ball stays positively oriented, else as far toward
// it as it can (the step halved up to five times) and waits for the next
// projection pass, after the reconnection around it. A vertex that still
// cannot reach the model at the end is collapsed onto a neighbour on the
// boundary (collapse_off_model).
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/boundary_placement.hpp>
#include <metrica/operators/collapse.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/pass_scope.hpp>
#include <metrica/operators/smooth.hpp>

namespace metrica {

struct ProjectionOptions {
  // A vertex this close to its entity's point is on the model.
  double tolerance = 1e-10;
  // A move may not make a tet of the ball worse than this (unless one
  // already was).
  double shape_floor = ShapeFloors::projection;
  // The metric a moved vertex takes at its new position.
  PassScope scope{};
};

template <MetricSpace S, Geometry G>
struct Projection : VertexMoveSteps {
  static constexpr std::string_view name = "project";
  ProjectionOptions options;
  G geometry{};

  Decision<Plan> decide(const Mesh& mesh, VertexId v, Scratch& s) const {
    if (!mesh.has_geo_params() || !mesh.geo_param(v).valid() || mesh.is_fixed(v)) return Refusal::not_applicable;
    const Point x = mesh.point(v);
    const Point target = geometry.point(mesh.geo_param(v));
    if ((target - x).norm() <= options.tolerance) return Refusal::not_applicable;
    auto r = Acceptance<S, ShapeOnly>(options.shape_floor).replacing(mesh, view(s.ball));
    auto keeps_shape_at = [&](const Point& p) {
      for (TetId t : s.ball)
        if (!r.shape_admits(mesh.tet(t), tet_points_moved(mesh, mesh.tet(t), v, p))) return false;
      return true;
    };
    const auto q = backtrack_toward(
        x, target, [&](const Point& p) { return ball_positive_at(mesh, v, s.ball, p) && keeps_shape_at(p); });
    if (!q) return Refusal::rejected;
    return Plan{*q, GeoParam{}};  // the vertex keeps its parameters
  }
  void apply(Mesh& mesh, VertexId v, const Plan& plan, Scratch& s) const {
    apply_smoothing(mesh, v, plan, s, SmoothOptions{.scope = {.metric = options.scope.metric}});
  }
};

// The boundary vertices farther than o.tolerance from their entity's point.
template <Concurrency C, Geometry G>
std::vector<VertexId> vertices_off_model(const Mesh& mesh, const G& geometry, double tolerance) {
  if (!mesh.has_geo_params()) return {};
  return C::template collect<VertexId>(mesh.vertex_capacity(), [&](std::size_t i, std::vector<VertexId>& part) {
    const auto v = static_cast<VertexId>(i);
    if (!mesh.vertex_alive(v) || !mesh.geo_param(v).valid() || !geometry.places(mesh, v)) return;
    if ((geometry.point(mesh.geo_param(v)) - mesh.point(v)).norm() > tolerance) part.emplace_back(v);
  });
}

// The projection pass: every boundary vertex off the model.
template <MetricSpace S, Concurrency C, Geometry G>
OperatorStats project_to_model(Mesh& mesh, const ProjectionOptions& o, const G& geometry) {
  Stopwatch clock;
  const auto todo = vertices_off_model<C>(mesh, geometry, o.tolerance);
  OperatorStats stats;
  if (!todo.empty()) stats = run_pass<C>(mesh, Projection<S, G>{{}, o, geometry}, todo);
  stats.seconds = clock.seconds();
  return stats;
}

// The last resort for the vertices in `off` (off the model, their
// projection refused): each is collapsed onto one of its neighbours along
// a boundary edge, at any length and shape, when the Geometry's rules
// and a positive ball allow it (serial: few vertices, outside a pass). Returns the stats; the vertices that stay are
// the caller's to report.
template <MetricSpace S, Geometry G>
OperatorStats collapse_off_model(Mesh& mesh, std::span<const VertexId> off, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  CollapseScratch s;
  // Onto a neighbour along a boundary edge.
  auto on_boundary = [&](VertexId u) { return mesh.has_geo_params() && mesh.geo_param(u).valid(); };
  for (VertexId v : off) {
    if (!mesh.vertex_alive(v)) continue;
    ++stats.tried;
    const AnyCollapse c = collapse_onto_any_neighbour<S>(mesh, v, s, geometry, on_boundary);
    stats.candidates += c.weighed;
    ++(c.done ? stats.applied : stats.rejected);
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
