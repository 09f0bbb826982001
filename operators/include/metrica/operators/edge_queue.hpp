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
// equal) the order stays longest / shortest first to that factor, and a
// 942k-tet run took 29.4 s against 32.6 s with the same share of edges in
// range (coarser classes: docs/benchmarks.md).
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/policies/concurrency.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
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
  // The lengths that are not beyond the bound.
  const UnitBand inside = longer ? UnitBand{0.0, bound} : UnitBand{bound, std::numeric_limits<double>::infinity()};
  const std::vector<std::uint8_t> changed =
      changed_since > 0 ? changed_vertices<C>(mesh, changed_since) : std::vector<std::uint8_t>{};
  std::vector<EdgeCandidate> out =
      collect_mesh_edges<C, EdgeCandidate>(mesh, [&](VertexId a, VertexId b, std::vector<EdgeCandidate>& part) {
        if (!changed.empty() && !changed[a] && !changed[b]) return;
        if (S::edge_length_in(mesh, a, b, inside)) return;
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
