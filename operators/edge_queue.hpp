// The work list of the edge operators (split, collapse): the edges whose
// metric length is outside a bound, ordered by length (longest first for
// splits, shortest first for collapses), ties broken by vertex ids so a
// run is reproducible.
#pragma once

#include <metrica/operators/edge_buckets.hpp>
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
  std::vector<EdgeCandidate> out =
      collect_mesh_edges<C, EdgeCandidate>(mesh, [&](VertexId a, VertexId b, std::vector<EdgeCandidate>& part) {
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
