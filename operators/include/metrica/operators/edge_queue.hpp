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
#include <utility>
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

// The edges whose length was outside the unit band when a full scan
// listed them (a cycle's conformity count does), with the mesh's epoch
// and compaction count at that moment: with the vertices changed since,
// the edges beyond a bound outside the band follow without a scan of
// every edge (edges_beyond).
struct OutOfBandEdges {
  Mesh::Epoch epoch = 0;  // tets written from this epoch on came later (0: never taken)
  std::uint32_t renumberings = 0;
  std::vector<std::pair<VertexId, VertexId>> edges;  // a < b
  // `edges` now lists the mesh's edges outside kUnitBand: a new epoch starts.
  void taken(Mesh& mesh) {
    epoch = mesh.next_epoch();
    renumberings = mesh.renumberings();
  }
};

namespace detail {
// The edges beyond a bound (on the side of `longer`) from `known`, as
// candidate(a, b, part) with a < b appends them, into `out`; false when
// `known` cannot give them: it is missing, taken before the last
// compaction, or the band holds lengths beyond the bound, or more than a
// quarter of the vertices changed since it was taken (listing their
// edges from their balls then costs about a full scan). An edge whose
// two ends did not change since has the length it had, every move or
// metric change of a vertex writing its ball, and exists still (removing
// it writes both balls): it is beyond the bound now iff it was, and was
// outside the band then. The edges at the changed vertices are listed
// from their balls, each once.
template <class C, class Candidate>
bool edges_from_known(const Mesh& mesh, double bound, bool longer, const OutOfBandEdges* known, Candidate&& candidate,
                      std::vector<EdgeCandidate>& out) {
  if (known == nullptr || known->epoch == 0 || known->renumberings != mesh.renumberings()) return false;
  if (longer ? bound < kUnitBand.hi : bound > kUnitBand.lo) return false;
  const std::vector<std::uint8_t> moved = changed_vertices<C>(mesh, known->epoch);
  const std::vector<VertexId> around =
      C::template collect<VertexId>(moved.size(), [&](std::size_t v, std::vector<VertexId>& part) {
        if (moved[v] != 0) part.emplace_back(static_cast<VertexId>(v));
      });
  if (4 * around.size() > mesh.num_vertices()) return false;
  out = C::template collect<EdgeCandidate>(known->edges.size(), [&](std::size_t i, std::vector<EdgeCandidate>& part) {
    const auto [a, b] = known->edges[i];
    if (mesh.vertex_alive(a) && mesh.vertex_alive(b) && moved[a] == 0 && moved[b] == 0) candidate(a, b, part);
  });
  const std::vector<EdgeCandidate> changed =
      C::template collect<EdgeCandidate>(around.size(), [&](std::size_t i, std::vector<EdgeCandidate>& part) {
        const VertexId a = around[i];
        TetList ball;
        VertexList neighbours;
        vertex_ball(mesh, a, ball);
        vertex_neighbours(mesh, ball, a, neighbours);
        for (VertexId b : neighbours)
          if (moved[b] == 0 || a < b) candidate(std::min(a, b), std::max(a, b), part);
      });
  out.insert(out.end(), changed.begin(), changed.end());
  return true;
}
}  // namespace detail

// Edges longer than `bound` (longest_first) or shorter (shortest_first);
// the lengths measured on C's threads. With `changed_since` > 0, only the
// edges with an end whose ball changed since that epoch (an edge
// operator reads the balls of its ends only), left out before they are
// measured and sorted. With `known`, from it and the vertices changed
// since it was taken when it can (detail::edges_from_known), else from
// all the mesh's edges: the same list either way.
template <MetricSpace S, class C = Serial>
std::vector<EdgeCandidate> edges_beyond(const Mesh& mesh, double bound, EdgeOrder order, Mesh::Epoch changed_since = 0,
                                        const OutOfBandEdges* known = nullptr) {
  const bool longer = order == EdgeOrder::longest_first;
  // The lengths that are not beyond the bound.
  const UnitBand inside = longer ? UnitBand{0.0, bound} : UnitBand{bound, std::numeric_limits<double>::infinity()};
  const std::vector<std::uint8_t> changed =
      changed_since > 0 ? changed_vertices<C>(mesh, changed_since) : std::vector<std::uint8_t>{};
  auto candidate = [&](VertexId a, VertexId b, std::vector<EdgeCandidate>& part) {
    if (!changed.empty() && !changed[a] && !changed[b]) return;
    if (S::edge_length_in(mesh, a, b, inside)) return;
    const double l = S::edge_length(mesh, a, b);
    if (longer ? l > bound : l < bound) part.emplace_back(EdgeCandidate{length_class(l), a, b});
  };
  std::vector<EdgeCandidate> out;
  if (!detail::edges_from_known<C>(mesh, bound, longer, known, candidate, out))
    out = collect_mesh_edges<C, EdgeCandidate>(mesh, candidate);
  // (length class, a, b) orders the edges totally: the order does not
  // depend on how they were gathered.
  C::sort(out.begin(), out.end(), [longer](const EdgeCandidate& x, const EdgeCandidate& y) {
    if (x.length_class != y.length_class)
      return longer ? x.length_class > y.length_class : x.length_class < y.length_class;
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  return out;
}

}  // namespace metrica
