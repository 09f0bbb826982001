// Where an operation puts a new boundary vertex under a Geometry policy
// (geometry/model.hpp). Its parameters come from its parents (the
// Geometry interpolates them); its point is the model's there when the
// cavity accepts it, else a point halfway back toward the straight
// position, up to five times (the paper's backtracking), else the
// straight position itself. A vertex left off the model is moved onto it
// later by the projection pass (project.hpp), once the reconnection
// around it has made room.
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/operators/shell.hpp>

#include <optional>

namespace metrica {

// The new vertex: its point and its parameters (invalid: not on a model).
struct BoundaryPoint {
  Point p;
  GeoParam geo;
};

inline constexpr int kBacktrackSteps = 5;

// The paper's backtracking: `target` if `accepts` takes it, else the
// first of the points halfway back toward `from`, kBacktrackSteps times,
// that it takes; none when it takes none.
template <class Accepts>
std::optional<Point> backtrack_toward(const Point& from, const Point& target, Accepts&& accepts) {
  Eigen::Vector3d step = target - from;
  for (int k = 0; k <= kBacktrackSteps; ++k, step *= 0.5) {
    const Point q = from + step;
    if (accepts(q)) return q;
  }
  return std::nullopt;
}

// `accepts(q)`: does the cavity accept the new vertex at q?
template <Geometry G, class Accepts>
BoundaryPoint place_boundary_vertex(const G& geometry, const GeoParam& param, const Point& straight,
                                    Accepts&& accepts) {
  if (!param.valid()) return {straight, {}};
  if (const auto q = backtrack_toward(straight, geometry.point(param), accepts)) return {*q, param};
  return {straight, param};
}

// The surface of edge ab: for a boundary edge (an open shell) the surface
// id of the first shell tet's boundary face through ab; for an edge of an
// internal surface (a closed shell) that surface's id; 0 for an inner edge.
inline SurfaceId edge_surface(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b) {
  if (shell.tets.empty()) return 0;
  if (shell.closed) {
    if (!mesh.has_internal_surfaces()) return 0;
    for (TetId t : shell.tets) {
      const auto& v = mesh.tet(t);
      for (int f = 0; f < 4; ++f)
        if (v[f] != a && v[f] != b && mesh.internal_surface_id(t, f) != 0) return mesh.internal_surface_id(t, f);
    }
    return 0;
  }
  for (TetId t : {shell.tets.front(), shell.tets.back()}) {
    const auto& v = mesh.tet(t);
    for (int f = 0; f < 4; ++f)
      if (v[f] != a && v[f] != b && !mesh.neighbour(t, f).valid()) return mesh.surface_id(t, f);
  }
  return 0;
}

// Parameters of a new vertex on surface edge ab (boundary or internal) at
// a + t (b - a): on the curve of a ridge edge, else on the edge's surface;
// none for an inner edge or without a model.
template <Geometry G>
GeoParam edge_vertex_param(const G& geometry, const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, double t) {
  const bool ridge = mesh.is_ridge(a, b);
  const SurfaceId surface = ridge ? 0 : edge_surface(mesh, shell, a, b);
  if (shell.closed && !ridge && surface == 0) return {};
  const std::array<VertexId, 2> ends{a, b};
  const std::array<double, 2> w{1.0 - t, t};
  return geometry.boundary_vertex(mesh, ends, w, surface);
}

}  // namespace metrica
