// What `metrica info` prints: counts, extent, surfaces (outer and
// internal), regions, ridges, volume.
#pragma once

#include <metrica/mesh.hpp>

#include <map>

namespace metrica {

struct SurfaceSummary {
  std::size_t faces = 0;
  double area = 0.0;
  bool internal = false;  // faces with a tet on both sides
};

struct RegionSummary {
  std::size_t tets = 0;
  double volume = 0.0;
};

struct MeshSummary {
  std::size_t vertices = 0, tets = 0, boundary_faces = 0, internal_faces = 0;
  std::size_t interior_vertices = 0, surface_vertices = 0, ridge_vertices = 0, corners = 0;
  std::size_t ridge_edges = 0, ridge_curves = 0, required_vertices = 0;
  Point lo = Point::Zero(), hi = Point::Zero();
  double volume = 0.0, min_tet_volume = 0.0, max_tet_volume = 0.0;
  std::map<SurfaceId, SurfaceSummary> surfaces;
  std::map<int, RegionSummary> regions;  // by tet ref
};

MeshSummary summarize(const Mesh& mesh);

}  // namespace metrica
