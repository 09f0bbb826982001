// The work list of the edge operators (split, collapse): the edges whose
// metric length is outside a bound, ordered by length class (longest
// first for splits, shortest first for collapses) and, within a class, by
// vertex ids, so a run is reproducible.
//
// Why classes and not exact lengths: a list sorted by exact length visits
// the mesh in random order, each item a fresh cache miss. Within one class
// the items follow the vertex ids, which compaction lays along a Morton
// curve, so consecutive items are near in space and in memory. With 8
// classes per doubling (lengths within a factor 2^(1/8) = 1.09 count as
// equal) the order stays longest / shortest first to that factor. At
// 942k tets on one thread (three interleaved runs each way) the collapse
// loop fell from 7.0-7.9 s to 5.9-6.2 s, the split loop from 1.95-2.01 s
// to 1.64-1.70 s, the whole run from 32.6 to 29.4 s (median), with the
// same share of edges in range. Coarser classes for the splits (2 or 4
// per doubling) made the run slower, 36-41 s against 28-29 s, at a
// slightly lower share in range (not looked into further: longest first
// matters for splits). For the collapses 2, 4 and 8 were within 1%; 16
// was no faster than 8.
#pragma once

#include <metrica/operators/edge_buckets.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/policies/concurrency.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace metrica {

inline constexpr double kLengthClassesPerDoubling = 8.0;

// floor(8 log2 l): the class of a metric length (l > 0).
inline std::int32_t length_class(double length) {
  return static_cast<std::int32_t>(std::floor(kLengthClassesPerDoubling * std::log2(std::max(length, 1e-30))));
}

struct EdgeCandidate {
  std::int32_t length_class;
  VertexId a, b;
  friend bool operator==(const EdgeCandidate&, const EdgeCandidate&) = default;
};

enum class EdgeOrder { longest_first, shortest_first };

// Edges longer than `bound` (longest_first) or shorter (shortest_first);
// the lengths measured on C's threads. With `changed_since` > 0, only the
// edges with an end whose ball changed since that epoch (an edge
// operator reads the balls of its ends only), left out before they are
// measured and sorted.
template <MetricSpace S, class C = Serial>
std::vector<EdgeCandidate> edges_beyond(const Mesh& mesh, double bound, EdgeOrder order,
                                        Mesh::Epoch changed_since = 0) {
  const bool longer = order == EdgeOrder::longest_first;
  const std::vector<std::uint8_t> changed =
      changed_since > 0 ? changed_vertices<C>(mesh, changed_since) : std::vector<std::uint8_t>{};
  std::vector<EdgeCandidate> out =
      collect_mesh_edges<C, EdgeCandidate>(mesh, [&](VertexId a, VertexId b, std::vector<EdgeCandidate>& part) {
        if (!changed.empty() && !changed[a] && !changed[b]) return;
        const double l = S::edge_length(mesh, a, b);
        if (longer ? l > bound : l < bound) part.push_back({length_class(l), a, b});
      });
  C::sort(out.begin(), out.end(), [longer](const EdgeCandidate& x, const EdgeCandidate& y) {
    if (x.length_class != y.length_class)
      return longer ? x.length_class > y.length_class : x.length_class < y.length_class;
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  return out;
}

}  // namespace metrica
