#include <metrica/mesh_edges.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>

namespace metrica {

void count_edges_by_lower_vertex(const Mesh& mesh, std::vector<std::uint32_t>& start) {
  const std::size_t nv = mesh.vertex_capacity();
  start.assign(nv + 1, 0);
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    for (const auto& e : kEdgeVertex) ++start[std::min(v[e[0]], v[e[1]]) + 1];
  }
  for (std::size_t i = 0; i < nv; ++i) start[i + 1] += start[i];
}

void edges_by_lower_vertex(const Mesh& mesh, const std::vector<std::uint32_t>& start, VertexId lo, VertexId hi,
                           std::vector<VertexId>& upper) {
  upper.resize(start[hi] - start[lo]);
  std::vector<std::uint32_t> cursor(start.begin() + lo, start.begin() + hi);
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    for (const auto& e : kEdgeVertex) {
      const VertexId a = std::min(v[e[0]], v[e[1]]);
      if (a < lo || a >= hi) continue;
      upper[cursor[a - lo]++ - start[lo]] = std::max(v[e[0]], v[e[1]]);
    }
  }
}

std::size_t edge_ranges(std::size_t entries, std::size_t max_ranges) {
  constexpr std::size_t kRangeBytes = std::size_t{4} << 20;
  return std::clamp<std::size_t>((entries * sizeof(VertexId) + kRangeBytes - 1) / kRangeBytes, 1,
                                 std::max<std::size_t>(max_ranges, 1));
}

// A bucket sort by the lower vertex (one counting pass, one filling pass),
// then each vertex's short list of higher neighbours sorted and made
// unique: the same order as sorting the edge keys, about four times
// faster than std::sort on 6 keys per tet (it ran in every operator pass).
std::vector<EdgeVertices> unique_edges(const Mesh& mesh) {
  std::vector<EdgeVertices> edges;
  edges.reserve(mesh.num_tets() * 6 / 4);
  for_each_unique_edge(mesh, [&](VertexId a, VertexId b) { edges.push_back({a, b}); });
  return edges;
}

}  // namespace metrica
