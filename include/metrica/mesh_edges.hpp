// The unique edges of a mesh, for loops over edges (gradation, quality
// reports, point creation by edges). A snapshot, sorted by (low, high) id.
#pragma once

#include <metrica/mesh.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace metrica {

// The higher ends of the edges, bucketed by lower end (with repeats):
// bucket a is upper[start[a] .. start[a + 1]).
void edges_by_lower_vertex(const Mesh& mesh, std::vector<std::uint32_t>& start, std::vector<VertexId>& upper);

// f(a, b) for each edge, a < b, in the order of unique_edges, without
// holding the list (a report over every edge of a large mesh).
template <class F>
void for_each_unique_edge(const Mesh& mesh, F&& f) {
  std::vector<std::uint32_t> start;
  std::vector<VertexId> upper;
  edges_by_lower_vertex(mesh, start, upper);
  for (VertexId a = 0; a < mesh.vertex_capacity(); ++a) {
    const auto first = upper.begin() + start[a], last = upper.begin() + start[a + 1];
    std::sort(first, last);
    for (auto it = first; it != last; ++it)
      if (it == first || *it != *(it - 1)) f(a, *it);
  }
}

std::vector<EdgeVertices> unique_edges(const Mesh& mesh);
// (The operators' passes build their edge lists on their policy's threads:
// operators/edge_buckets.hpp.)

}  // namespace metrica
