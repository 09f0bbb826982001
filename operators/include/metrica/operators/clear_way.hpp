// Clearing the way to the model: an inner vertex (one off the boundary)
// close to a curved internal surface can stand where the split of one of
// its edges should put the new vertex on the model, so that the split's
// tets would invert. On an internal surface such a split waits (both
// regions hold the vertex: no later pass could move it onto the model),
// and its long edge would stay under the worst tets; the inner vertex is
// collapsed away instead (clear_way_for_splits).
#pragma once

#include <metrica/operators/collapse.hpp>
#include <metrica/operators/split_edge.hpp>

namespace metrica {

// The collapse that clears the way: onto the neighbour that leaves the
// best ball, no new tet below the repair rounds' threshold (0.3) unless it
// beats the ball's worst; at any shape, the tets it left stayed below 0.3
// in some runs to the end.
inline constexpr AnyCollapseRule kClearingCollapse{.shape_floor = 0.3, .best = true};

// An inner vertex that may be collapsed away.
inline bool removable_inner_vertex(const Mesh& mesh, VertexId w) {
  return !(mesh.has_geo_params() && mesh.geo_param(w).valid()) && !mesh.is_fixed(w) &&
         mesh.vertex_class(w) == VertexClass::interior;
}

// The internal-surface edges longer than o.max_length whose model point
// the shell cannot take (a child of the split would not be positive):
// the inner vertices of those children are collapsed away, so that the
// next split pass splits the edge on the model. Serial (the edges are
// few: those their split pass left); `tried` counts the blocked edges,
// `applied` those with a vertex removed, `candidates` the vertices weighed.
template <MetricSpace S, Concurrency C, Geometry G>
OperatorStats clear_way_for_splits(Mesh& mesh, const RefineOptions& o, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  if (geometry.on_model()) {
    if (mesh.has_internal_surfaces() && mesh.has_geo_params()) {
      const auto todo = edges_beyond<S, C>(mesh, o.max_length, EdgeOrder::longest_first, o.scope.changed_since);
      TetList ball;
      Shell shell;
      VertexList in_the_way;
      CollapseScratch cs;
      auto any_neighbour = [](VertexId) { return true; };
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
          if (positive_tet(x[0], x[1], x[2], x[3])) return true;
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
          if (mesh.vertex_alive(w) &&
              collapse_onto_any_neighbour<S>(mesh, w, cs, geometry, any_neighbour, kClearingCollapse).done)
            cleared = true;
        }
        ++(cleared ? stats.applied : stats.rejected);
      }
    }
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
