// Work lists in id order without a comparison sort: a pass lists what to
// try by id and wants each once in id order (after compact() that is
// space order, the seed's buckets for locality). Ids are bounded by the
// mesh's capacity, so marks or buckets order them in linear time
// (smoothing lists its vertices from marks, smooth.hpp).
#pragma once

#include <metrica/ids.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace metrica {

// An edge and a tet that holds it (the tet is where a shell walk starts).
// Three 32-bit words, not a 64-bit key and a padded id: a flip pass lists
// every edge of its seeds (16 bytes each were the pass's peak).
struct EdgeSeed {
  EdgeSeed() = default;
  EdgeSeed(std::uint64_t edge, TetId holder)
      : lower(static_cast<VertexId>(edge >> 32)), higher(static_cast<VertexId>(edge)), tet(holder) {}
  std::uint64_t key() const { return (std::uint64_t{lower} << 32) | higher; }  // edge_key(lower, higher)
  EdgeVertices ends() const { return {lower, higher}; }
  VertexId lower, higher;
  TetId tet;
};
static_assert(sizeof(EdgeSeed) == 12);

// The distinct edges of `tets`, each with the first tet of `tets` that
// holds it, ordered by key (lower vertex, then higher): what sorting the
// 6 edges of every tet by key and keeping the first of each run gives.
// `vertices_of(t)` gives tet t's vertices, each below `capacity`. Edge
// buckets (edge_buckets.hpp) on C's threads, the same list for any number
// of threads, in linear time (no sort of the 6 keys per tet, about five
// repeats of each edge).
//
// The buckets hold only the higher vertex of each edge (4 bytes per tet
// edge, not 8 with its tet), and they are made for a range of lower ends
// at a time (lower_ranges), each range's
// edges appended to `out`, whose capacity is reserved for 6 edges per
// tet (a mapped block: what is never written is never resident), so it
// does not move: these buckets were the peak of the first flip pass of
// the quality phase. A second sweep over `tets` then gives each edge the
// smallest index in `tets` among those holding it (an atomic minimum, so
// the same for any order of the parts).
template <class C = Serial, class VerticesOf, class Out>
void unique_edge_seeds(std::span<const TetId> tets, VerticesOf&& vertices_of, std::size_t capacity, Out& out) {
  const std::size_t parts = sweep_parts<C>(tets.size());
  // Bucket a's edges start at first[a] in `out` (count[a] of them); every
  // lower end of an edge of `tets` is written by its range.
  MeshArray<std::uint32_t> first, count;
  first.resize(capacity);
  count.resize(capacity);
  out.clear();
  out.reserve(6 * tets.size());
  struct alignas(64) Cursor {
    std::size_t at = 0;
  };
  std::vector<Cursor> cursor(parts);
  for (const LowerRange& range : lower_ranges(tets.size(), capacity)) {
    // Each part writes its edges straight into `out`, from its offset on.
    for_each_edge_bucket<C, VertexId>(
        parts, tets.size(), [&](std::size_t i) { return tets[i]; }, vertices_of, range, true,
        [&](std::size_t p, VertexId a, std::span<const VertexId> kept) {
          std::size_t& at = cursor[p].at;
          first[a] = static_cast<std::uint32_t>(at);
          count[a] = static_cast<std::uint32_t>(kept.size());
          for (VertexId b : kept) out[at++] = EdgeSeed{edge_key(a, b), kNoId};
        },
        [&](std::span<const std::size_t> edges_in) {
          std::size_t total = out.size();
          for (std::size_t p = 0; p < parts; ++p) {
            cursor[p].at = total;
            total += edges_in[p];
          }
          out.resize(total);
        });
  }
  // Each edge's first holder: the smallest index i of `tets`.
  C::parallel_for(parts, [&](std::size_t p) {
    const auto [lo, hi] = part_slice(tets.size(), parts, p);
    for (std::size_t i = lo; i < hi; ++i) {
      const TetVertices& v = vertices_of(tets[i]);
      for (const auto& e : kEdgeVertex) {
        const VertexId a = std::min(v[e[0]], v[e[1]]), b = std::max(v[e[0]], v[e[1]]);
        EdgeSeed* const begin = out.data() + first[a];
        EdgeSeed* const end = begin + count[a];
        const std::uint64_t key = edge_key(a, b);
        EdgeSeed* x = std::lower_bound(begin, end, key, [](const EdgeSeed& s, std::uint64_t k) { return s.key() < k; });
        std::atomic_ref<TetId> holder(x->tet);
        TetId seen = holder.load(std::memory_order_relaxed);
        const auto mine = static_cast<TetId>(i);
        while (mine < seen && !holder.compare_exchange_weak(seen, mine, std::memory_order_relaxed)) {
        }
      }
    }
  });
  C::parallel_for(parts, [&](std::size_t p) {
    const auto [lo, hi] = part_slice(out.size(), parts, p);
    for (std::size_t k = lo; k < hi; ++k) out[k].tet = tets[out[k].tet];
  });
}

}  // namespace metrica
