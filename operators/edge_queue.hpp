// The work list of the edge operators (split, collapse): the edges whose
// metric length is outside a bound, ordered by length (longest first for
// splits, shortest first for collapses), ties broken by vertex ids so a
// run is reproducible.
#pragma once

#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/policies/concurrency.hpp>

#include <algorithm>
#include <vector>

namespace metrica {

struct EdgeCandidate {
  double length;
  VertexId a, b;
};

enum class EdgeOrder { longest_first, shortest_first };

// Edges longer than `bound` (longest_first) or shorter (shortest_first);
// the lengths measured on C's threads.
template <MetricSpace S, class C = Serial>
std::vector<EdgeCandidate> edges_beyond(const Mesh& mesh, double bound, EdgeOrder order) {
  const bool longer = order == EdgeOrder::longest_first;
  const auto edges = unique_edges_unordered(mesh);
  std::vector<EdgeCandidate> out =
      C::template collect<EdgeCandidate>(edges.size(), [&](std::size_t i, std::vector<EdgeCandidate>& part) {
        const auto [a, b] = edges[i];
        const double l = S::edge_length(mesh, a, b);
        if (longer ? l > bound : l < bound) part.push_back({l, a, b});
      });
  C::sort(out.begin(), out.end(), [longer](const EdgeCandidate& x, const EdgeCandidate& y) {
    if (x.length != y.length) return longer ? x.length > y.length : x.length < y.length;
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  return out;
}

}  // namespace metrica
