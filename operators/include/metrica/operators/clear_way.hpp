// Clearing the way to the model: an inner vertex (one off the boundary)
// close to a curved surface can stand where a boundary vertex should go on
// the model, so that every tet joining the two would invert. Such inner
// vertices are collapsed away, for a boundary vertex off the model
// (clear_way_to_model, the projection's last resort) and for a split of an
// internal-surface edge whose model point the mesh cannot take
// (clear_way_for_splits: on an internal surface such a split waits, and
// its long edge would stay under the worst tets).
#pragma once

#include <metrica/operators/collapse.hpp>
#include <metrica/operators/project.hpp>
#include <metrica/operators/split_edge.hpp>

namespace metrica {

// Removes inner vertex w by a collapse onto `prefer`, else onto another of
// its neighbours, at any length and shape but a non-positive tet; false
// when none is admitted. Serial.
template <MetricSpace S, Precision P, Geometry G>
bool collapse_inner_vertex(Mesh& mesh, VertexId w, VertexId prefer, CollapseScratch& cs, const G& geometry) {
  CollapseOptions any;
  any.min_length = std::numeric_limits<double>::infinity();
  any.max_new_length = std::numeric_limits<double>::infinity();
  any.shape_floor = 0.0;
  vertex_ball(mesh, w, cs.ball);
  vertex_neighbours(mesh, cs.ball, w, cs.neighbours);
  VertexList targets;
  if (prefer != kNoId) targets.emplace_back(prefer);
  for (VertexId u : cs.neighbours)
    if (u != prefer) targets.emplace_back(u);
  for (VertexId u : targets) {
    vertex_ball(mesh, w, cs.ball);
    vertex_neighbours(mesh, cs.ball, w, cs.neighbours);
    vertex_ball(mesh, u, cs.ball_b);
    vertex_neighbours(mesh, cs.ball_b, u, cs.neighbours_b);
    const auto d = decide_collapse<S, P, ShapeOnly>(mesh, w, u, cs, any, nullptr, nullptr, geometry);
    if (!d) continue;
    apply_collapse(mesh, d.plan(), cs);
    return true;
  }
  return false;
}

// An inner vertex that may be collapsed away.
inline bool removable_inner_vertex(const Mesh& mesh, VertexId w) {
  return !(mesh.has_geo_params() && mesh.geo_param(w).valid()) && !mesh.is_fixed(w) &&
         mesh.vertex_class(w) == VertexClass::interior;
}

// A last resort for the vertices in `off` (off the model, their
// projection refused because tets of their ball would invert at the model
// point): each tet in the way whose inner vertex (one off the boundary)
// sits between the vertex and its model point loses it, collapsed onto
// the vertex or another neighbour, at any length and shape but a
// non-positive tet; then the vertex moves as far toward its point as its
// new ball allows, a few rounds per vertex (serial: few vertices, outside
// a pass). The flips and smoothing that follow lift what this leaves.
template <MetricSpace S, Precision P, Geometry G>
OperatorStats clear_way_to_model(Mesh& mesh, std::span<const VertexId> off, const ProjectionOptions& o,
                                 const G& geometry) {
  constexpr int kRounds = 8;
  Stopwatch clock;
  OperatorStats stats;
  const Projection<S, P, G> projection{{}, o, geometry};
  CollapseScratch cs;
  SmoothScratch ms;
  TetList ball;
  // Removes one inner vertex in v's way; false when none can go.
  auto clear_one = [&](VertexId v, const Point& target) {
    vertex_ball(mesh, v, ball);
    for (std::size_t i = 0; i < ball.size(); ++i) {
      const TetVertices tv = mesh.tet(ball[i]);
      const TetPoints moved = tet_points_moved(mesh, tv, v, target);
      if (P::orient3d(moved[0], moved[1], moved[2], moved[3]) > 0) continue;
      for (VertexId w : tv)
        if (w != v && removable_inner_vertex(mesh, w) && collapse_inner_vertex<S, P>(mesh, w, v, cs, geometry))
          return true;
    }
    return false;
  };
  for (VertexId v : off) {
    if (!mesh.vertex_alive(v)) continue;
    ++stats.tried;
    const Point target = geometry.point(mesh.geo_param(v));
    auto on_model = [&] { return (target - mesh.point(v)).norm() <= o.tolerance; };
    for (int round = 0; round < kRounds && !on_model(); ++round) {
      if (round > 0 && !clear_one(v, target)) break;
      ++stats.candidates;
      find_smoothing_cavity(mesh, v, ms);
      if (const auto d = projection.decide(mesh, v, ms)) projection.apply(mesh, v, d.plan(), ms);
    }
    ++(on_model() ? stats.applied : stats.rejected);
  }
  stats.seconds = clock.seconds();
  return stats;
}

// The internal-surface edges longer than o.max_length whose model point
// the shell cannot take (a child of the split would not be positive):
// the inner vertices of those children are collapsed away, so that the
// next split pass splits the edge on the model. Serial (the edges are
// few: those their split pass left); `tried` counts the blocked edges,
// `applied` those with a vertex removed, `candidates` the vertices weighed.
template <MetricSpace S, Precision P, Concurrency C, Geometry G>
OperatorStats clear_way_for_splits(Mesh& mesh, const RefineOptions& o, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  if constexpr (G::on_model) {
    if (mesh.has_internal_surfaces() && mesh.has_geo_params()) {
      const auto todo = edges_beyond<S, C>(mesh, o.max_length, EdgeOrder::longest_first, o.scope.changed_since);
      TetList ball;
      Shell shell;
      VertexList in_the_way;
      CollapseScratch cs;
      for (const EdgeCandidate& c : todo) {
        if (!mesh.vertex_alive(c.a) || !mesh.vertex_alive(c.b)) continue;
        vertex_ball(mesh, c.a, ball);
        if (!edge_shell(mesh, c.a, c.b, ball, shell) || !shell.closed || mesh.is_required_edge(c.a, c.b)) continue;
        if (edge_surface(mesh, shell, c.a, c.b) == 0 && !mesh.is_ridge(c.a, c.b)) continue;
        const Eigen::Vector3d e = mesh.point(c.b) - mesh.point(c.a);
        const double t = metric_midpoint(std::sqrt(metric_norm2(S::vertex_metric(mesh, c.a), e)),
                                         std::sqrt(metric_norm2(S::vertex_metric(mesh, c.b), e)));
        const GeoParam param = edge_vertex_param(geometry, mesh, shell, c.a, c.b, t);
        if (!param.valid()) continue;
        const Point q = geometry.point(param);
        bool blocked = false;
        in_the_way.clear();
        all_split_children(mesh, shell, c.a, c.b, q, [&](TetId s, const TetVertices&, const TetPoints& x) {
          if (P::orient3d(x[0], x[1], x[2], x[3]) > 0) return true;
          blocked = true;
          for (VertexId w : mesh.tet(s))
            if (w != c.a && w != c.b && removable_inner_vertex(mesh, w) &&
                std::find(in_the_way.begin(), in_the_way.end(), w) == in_the_way.end())
              in_the_way.emplace_back(w);
          return true;
        });
        if (!blocked) continue;
        ++stats.tried;
        bool cleared = false;
        for (VertexId w : in_the_way) {
          ++stats.candidates;
          cleared = (mesh.vertex_alive(w) && collapse_inner_vertex<S, P>(mesh, w, kNoId, cs, geometry)) || cleared;
        }
        ++(cleared ? stats.applied : stats.rejected);
      }
    }
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
