#include <metrica/bucket_cursors.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace metrica {

void count_edges_by_lower_vertex(const Mesh& mesh, const PartRunner& run, LowerEdgeCounts& counts) {
  const std::size_t nv = mesh.vertex_capacity(), nt = mesh.tet_capacity();
  counts.parts = std::clamp<std::size_t>(run.parts, 1, LowerEdgeCounts::kMaxParts);
  count_keys(
      nt, nv, counts.parts,
      [&](std::size_t i, auto&& add) {
        const auto t = static_cast<TetId>(i);
        if (!mesh.tet_alive(t)) return;
        const auto& v = mesh.tet(t);
        for (const auto& e : kEdgeVertex) add(std::min(v[e[0]], v[e[1]]));
      },
      run, counts.count);
  // The buckets' starts over all parts: one pass over the vertices, on
  // this thread (the scans of the tets are what the parts share).
  counts.start.assign(nv + 1, 0);
  std::uint64_t at = 0;
  for (std::size_t a = 0; a < nv; ++a) {
    counts.start[a] = static_cast<std::uint32_t>(at);
    for (std::size_t p = 0; p < counts.parts; ++p) at += counts.count[p * nv + a];
    if (at > std::uint64_t{0xfffffffe})
      throw std::length_error("for_each_unique_edge: more than 2^32 - 2 edge entries");
  }
  counts.start[nv] = static_cast<std::uint32_t>(at);
}

void edges_by_lower_vertex(const Mesh& mesh, LowerEdgeCounts& counts, VertexId lo, VertexId hi, const PartRunner& run,
                           std::vector<VertexId>& upper) {
  const std::size_t nv = mesh.vertex_capacity(), nt = mesh.tet_capacity(), parts = counts.parts;
  MeshArray<std::uint32_t> range_start;
  upper.resize(cursors_of_counts(nv, lo, hi, parts, run, counts.count, range_start));
  run(parts, [&](std::size_t p) {
    std::uint32_t* cursor = counts.count.data() + p * nv;
    const auto [first, last] = part_slice(nt, parts, p);
    for (std::size_t i = first; i < last; ++i) {
      const auto t = static_cast<TetId>(i);
      if (!mesh.tet_alive(t)) continue;
      const auto& v = mesh.tet(t);
      for (const auto& e : kEdgeVertex) {
        const VertexId a = std::min(v[e[0]], v[e[1]]);
        if (a < lo || a >= hi) continue;
        upper[cursor[a]++] = std::max(v[e[0]], v[e[1]]);
      }
    }
  });
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
