#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/surface_angles.hpp>
#include <metrica/tet_topology.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace metrica {

AngleSplit split_surfaces_at_angle(Mesh& mesh, double degrees, std::span<const SurfaceId> ids) {
  AngleSplit out;
  if (!(degrees < 180.0) || ids.empty()) return out;
  struct Face {
    TetId t;
    int f;
    SurfaceId id;
    Eigen::Vector3d normal;
  };
  std::vector<Face> faces;
  SurfaceId largest = 0;
  for_each_boundary_face(mesh, [&](TetId t, int f) {
    const SurfaceId id = mesh.face_surface_id(t, f);
    largest = std::max(largest, id);
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) return;
    const auto v = face_vertices(mesh.tet(t), f);
    faces.push_back({t, f, id, face_normal(mesh, v[0], v[1], v[2]).normalized()});
  });
  if (mesh.has_internal_surfaces())
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t))
        for (int f = 0; f < 4; ++f) largest = std::max(largest, mesh.internal_surface_id(t, f));
  // The faces around each edge, by edge key.
  struct EdgeFace {
    std::uint64_t key;
    std::uint32_t face;
  };
  std::vector<EdgeFace> edges;
  edges.reserve(3 * faces.size());
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    const auto v = face_vertices(mesh.tet(faces[i].t), faces[i].f);
    for (int k = 0; k < 3; ++k) edges.push_back({edge_key(v[k], v[(k + 1) % 3]), i});
  }
  std::sort(edges.begin(), edges.end(),
            [](const EdgeFace& a, const EdgeFace& b) { return a.key < b.key || (a.key == b.key && a.face < b.face); });
  // Pieces by union-find over the edges a piece may cross.
  std::vector<std::uint32_t> parent(faces.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const double cos_limit = std::cos(degrees * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      const Face& a = faces[edges[i].face];
      const Face& b = faces[edges[i + 1].face];
      if (a.normal.dot(b.normal) >= cos_limit) {
        if (a.id == b.id) parent[root(edges[i].face)] = root(edges[i + 1].face);
      } else {
        const auto e = edge_from_key(edges[i].key);
        mesh.add_feature_edge(e[0], e[1]);
        ++out.sharp_edges;
      }
    }
    i = j;
  }
  // New ids: the first piece of each id (in face order) keeps it.
  std::vector<SurfaceId> piece_id(faces.size(), 0);
  std::vector<SurfaceId> kept;
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    const std::uint32_t r = root(i);
    if (piece_id[r] == 0) {
      const bool first = std::find(kept.begin(), kept.end(), faces[i].id) == kept.end();
      if (first) kept.push_back(faces[i].id);
      if (!first && largest + 1 >= kMaxSurfaceId)
        throw InputError(
            fmt::format("splitting the boundary at {} degrees makes more surfaces than a mesh holds "
                        "(ids up to {})",
                        degrees, kMaxSurfaceId - 1));
      piece_id[r] = first ? faces[i].id : ++largest;
      ++out.surfaces;
    }
    mesh.set_surface_id(faces[i].t, faces[i].f, piece_id[r]);
  }
  mesh.classify();
  return out;
}

}  // namespace metrica
