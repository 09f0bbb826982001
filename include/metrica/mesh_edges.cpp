#include <metrica/mesh_edges.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>

namespace metrica {

std::vector<EdgeVertices> unique_edges(const Mesh& mesh) {
  std::vector<std::uint64_t> keys;
  keys.reserve(6 * mesh.num_tets());
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    for (const auto& e : kEdgeVertex) keys.push_back(edge_key(v[e[0]], v[e[1]]));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<EdgeVertices> edges(keys.size());
  std::transform(keys.begin(), keys.end(), edges.begin(), edge_from_key);
  return edges;
}

}  // namespace metrica
