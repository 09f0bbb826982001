// The distinct edges of a set of tets, bucketed by lower vertex, built on
// the Concurrency policy's threads: what every edge pass starts from (the
// split and collapse work lists, the flips' edge seeds, the conformity of
// a cycle). Built on one thread they were the larger part of what a
// 2-thread adaptation did outside the operators' parallel loops.
//
// The items are cut into `parts` contiguous slices, one per thread:
//   1. each part counts its edges per lower vertex (its own counters);
//   2. bucket starts by a prefix sum over (vertex, part): bucket a holds
//      part 0's edges, then part 1's, each in item order, so the buckets
//      are those of one thread going through the items in order, for any
//      number of parts (1 and 2: bucket_cursors, shared with compaction);
//   3. each part scatters its edges to its own cursors;
//   4. slices of buckets of about equal size are made distinct in place
//      (the first entry of each higher vertex kept, with per-part marks),
//      each part counting what it kept;
//   5. `sizes` learns those counts, on the calling thread, so that the
//      caller can size its output once; then the slices are handed to
//      `visit`, all in parallel (lists grown by push_back instead would
//      serialise on their reallocations and first touches of new
//      memory).
// Linear in the edges, no comparison sort; 4 bytes of counters per vertex
// and part.
#pragma once

#include <metrica/bucket_cursors.hpp>
#include <metrica/ids.hpp>
#include <metrica/mesh.hpp>
#include <metrica/mesh_array.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace metrica {

// An entry of a bucket when the caller needs a tet holding the edge.
struct UpperTet {
  VertexId upper;
  TetId tet;
};

// For the items i < n with tet_of(i) != kNoId, the distinct edges of
// vertices_of(tet_of(i)) (each vertex below `capacity`): calls
// visit(part, a, kept) for every lower vertex a with an edge, where kept
// lists a's higher neighbours once each, in order of first appearance
// (or ascending when `sorted`), as `Entry`: VertexId (the higher vertex)
// or UpperTet (with the first item's tet). Parts run in parallel; within
// a part, a ascends, and part p's vertices all come before part p+1's.
// Before any visit, sizes(counts) gets each part's number of edges.
struct NoEdgeCounts {
  void operator()(std::span<const std::size_t>) const {}
};

// The edges whose lower end is in [lo, hi) only: buckets, counters and
// entries for that range (a whole mesh's edges listed in vertex ranges,
// for_each_mesh_edge_bucket, cost a fraction of listing them at once).
struct LowerRange {
  std::size_t lo = 0, hi = 0;
  std::size_t end = 0;  // every vertex id is below it (the higher ends too)
  // When set: count_keys of the same items over all `end` lower ends,
  // made once for every range (each range then scans the items once, to
  // scatter, not twice); this range's counts become its cursors.
  MeshArray<std::uint32_t>* counts = nullptr;
};

// The lower end of each of tet vertices v's edges, as add(a).
template <class Add>
void add_lower_ends(const TetVertices& v, Add&& add) {
  for (const auto& e : kEdgeVertex) add(std::min(v[e[0]], v[e[1]]));
}

template <class C, class Entry, class TetOf, class VerticesOf, class Visit, class Sizes = NoEdgeCounts>
void for_each_edge_bucket(std::size_t parts, std::size_t n, TetOf&& tet_of, VerticesOf&& vertices_of, LowerRange range,
                          bool sorted, Visit&& visit, Sizes&& sizes = {}) {
  static_assert(std::is_same_v<Entry, VertexId> || std::is_same_v<Entry, UpperTet>);
  parts = std::max<std::size_t>(parts, 1);
  const std::size_t lo = range.lo, cap = range.hi > range.lo ? range.hi - range.lo : 0;
  auto in_range = [lo, cap](VertexId a) { return static_cast<std::size_t>(a) - lo < cap; };  // wraps below lo
  // Per part: counters, then cursors (bucket_cursors); part p's cursor of
  // lower end a at cursor[p * stride + a - offset].
  MeshArray<std::uint32_t> own, start;
  MeshArray<std::uint32_t>& per_part = range.counts != nullptr ? *range.counts : own;
  const std::size_t stride = range.counts != nullptr ? range.end : cap, offset = range.counts != nullptr ? 0 : lo;
  auto items_of = [&](std::size_t p) { return part_slice(n, parts, p); };
  auto run = [](std::size_t k, auto&& f) { C::parallel_for(k, f); };
  const std::size_t total = range.counts != nullptr
                                ? cursors_of_counts(range.end, lo, lo + cap, parts, run, per_part, start)
                                : bucket_cursors(
                                      n, cap, parts,
                                      [&](std::size_t i, auto&& add) {
                                        const TetId t = tet_of(i);
                                        if (t == kNoId) return;
                                        add_lower_ends(vertices_of(t), [&](VertexId a) {
                                          if (in_range(a)) add(a - lo);
                                        });
                                      },
                                      run, own, start);
  MeshArray<Entry> entries;
  entries.resize(total);
  C::parallel_for(parts, [&](std::size_t p) {
    std::uint32_t* cursor = per_part.data() + p * stride;
    const auto [first, last] = items_of(p);
    for (std::size_t i = first; i < last; ++i) {
      const TetId t = tet_of(i);
      if (t == kNoId) continue;
      const TetVertices& v = vertices_of(t);
      for (const auto& e : kEdgeVertex) {
        const VertexId a = v[e[0]], b = v[e[1]];
        const VertexId lower = std::min(a, b);
        if (!in_range(lower)) continue;
        Entry& x = entries[cursor[lower - offset]++];
        if constexpr (std::is_same_v<Entry, UpperTet>)
          x = {std::max(a, b), t};
        else
          x = std::max(a, b);
      }
    }
  });
  own = {};
  // Slices of about total / parts entries, cut at bucket starts.
  std::vector<std::size_t> cut(parts + 1, cap);
  cut[0] = 0;
  for (std::size_t p = 1; p < parts; ++p)
    cut[p] = static_cast<std::size_t>(
        std::lower_bound(start.data(), start.data() + cap, static_cast<std::uint32_t>(total * p / parts)) -
        start.data());
  auto upper_of = [](const Entry& x) {
    if constexpr (std::is_same_v<Entry, UpperTet>)
      return x.upper;
    else
      return x;
  };
  // kept[a]: how many of bucket a's entries are distinct (at its front).
  // Per part, marks over the higher ends (which lie in [lo, range.end)):
  // last[b - lo] == a when edge ab is already kept.
  MeshArray<std::uint32_t> kept, marks;
  kept.resize(cap);
  const std::size_t uppers = range.end > lo ? range.end - lo : 0;
  marks.resize(parts * uppers);
  std::vector<std::size_t> edges_in(parts, 0);
  C::parallel_for(parts, [&](std::size_t p) {
    std::uint32_t* last = marks.data() + p * uppers;
    std::fill(last, last + uppers, kNoId);
    std::size_t edges = 0;
    for (std::size_t k = cut[p]; k < cut[p + 1]; ++k) {
      const auto a = static_cast<std::uint32_t>(lo + k);
      Entry* const first = entries.data() + start[k];
      Entry* end = first;
      for (Entry* x = first; x != entries.data() + start[k + 1]; ++x) {
        std::uint32_t& mark = last[upper_of(*x) - lo];
        if (mark == a) continue;
        mark = a;
        *end++ = *x;
      }
      // A handful of edges per vertex: insertion sort by the higher end.
      if (sorted && end - first > 1)
        for (Entry* i = first + 1; i < end; ++i)
          for (Entry* j = i; j > first && upper_of(*j) < upper_of(*(j - 1)); --j) std::swap(*j, *(j - 1));
      kept[k] = static_cast<std::uint32_t>(end - first);
      edges += kept[k];
    }
    edges_in[p] = edges;
  });
  sizes(std::span<const std::size_t>(edges_in));
  C::parallel_for(parts, [&](std::size_t p) {
    for (std::size_t k = cut[p]; k < cut[p + 1]; ++k)
      if (kept[k] > 0)
        visit(p, static_cast<VertexId>(lo + k), std::span<const Entry>(entries.data() + start[k], kept[k]));
  });
}

// Every lower end below `capacity`.
template <class C, class Entry, class TetOf, class VerticesOf, class Visit, class Sizes = NoEdgeCounts>
void for_each_edge_bucket(std::size_t parts, std::size_t n, TetOf&& tet_of, VerticesOf&& vertices_of,
                          std::size_t capacity, bool sorted, Visit&& visit, Sizes&& sizes = {}) {
  for_each_edge_bucket<C, Entry>(parts, n, tet_of, vertices_of, LowerRange{0, capacity, capacity}, sorted, visit,
                                 sizes);
}

// The lower-end ranges the edges of `tets` tets over vertex ids below
// `capacity` are listed in: edge_ranges of their 6 entries per tet, up to
// 4 (the edges of collapse and split and the flips' seed edges).
inline std::vector<LowerRange> lower_ranges(std::size_t tets, std::size_t capacity) {
  const std::size_t ranges = edge_ranges(6 * tets, 4);
  std::vector<LowerRange> out;
  for (std::size_t r = 0; r < ranges; ++r) {
    const auto [lo, hi] = part_slice(capacity, ranges, r);
    out.push_back({lo, hi, capacity});
  }
  return out;
}

struct NoRangeEnd {
  void operator()() const {}
};

// for_each_edge_bucket over the live tets of `mesh` (VertexId entries,
// unsorted), in `parts` parts (sweep_parts<C> of the tet capacity), range
// by range of lower ends (lower_ranges): for each range, sizes(counts)
// with its parts' numbers of edges, visit(part, a, kept) for its lower ends
// a, then range_end(). Lower ends ascend across ranges and parts. With
// several ranges the lower ends are counted for all in one scan (the
// per-range counting scans were a third of a conformity count at 4.3M
// tets, 4 ranges: 5 scans of the tets instead of 8).
template <class C, class Visit, class Sizes = NoEdgeCounts, class RangeEnd = NoRangeEnd>
void for_each_mesh_edge_bucket(const Mesh& mesh, std::size_t parts, Visit&& visit, Sizes&& sizes = {},
                               RangeEnd&& range_end = {}) {
  auto tet_of = [&](std::size_t i) { return mesh.tet_alive(static_cast<TetId>(i)) ? static_cast<TetId>(i) : kNoId; };
  auto vertices_of = [&](TetId t) -> const TetVertices& { return mesh.tet(t); };
  std::vector<LowerRange> ranges = lower_ranges(mesh.num_tets(), mesh.vertex_capacity());
  // Several ranges: the lower ends counted in one scan of the tets for all.
  MeshArray<std::uint32_t> counts;
  if (ranges.size() > 1) {
    count_keys(
        mesh.tet_capacity(), mesh.vertex_capacity(), parts,
        [&](std::size_t i, auto&& add) {
          if (const TetId t = tet_of(i); t != kNoId) add_lower_ends(vertices_of(t), add);
        },
        [](std::size_t k, auto&& f) { C::parallel_for(k, f); }, counts);
    for (LowerRange& r : ranges) r.counts = &counts;
  }
  for (const LowerRange& range : ranges) {
    for_each_edge_bucket<C, VertexId>(parts, mesh.tet_capacity(), tet_of, vertices_of, range, false, visit, sizes);
    range_end();
  }
}

// The distinct edges of the live tets of `mesh` as f(a, b, part) with a <
// b: each appends to `part` what edge ab contributes (mostly at most one
// item: each part's list is reserved for one per edge); the parts joined
// in order of a (and of first appearance within a), by the parts'
// threads: the order of one thread going through the tets by id.
template <class C, class T, class F>
std::vector<T> collect_mesh_edges(const Mesh& mesh, F&& f) {
  const std::size_t parts = sweep_parts<C>(mesh.tet_capacity());
  std::vector<std::vector<T>> out(parts);
  std::vector<T> all;
  for_each_mesh_edge_bucket<C>(
      mesh, parts,
      [&](std::size_t p, VertexId a, std::span<const VertexId> kept) {
        for (VertexId b : kept) f(a, b, out[p]);
      },
      [&](std::span<const std::size_t> edges_in) {
        for (std::size_t p = 0; p < parts; ++p) {
          out[p].clear();
          out[p].reserve(edges_in[p]);
        }
      },
      [&] {
        if (all.empty() && parts == 1) {
          all = std::move(out[0]);
          out[0] = {};
          return;
        }
        if (parts == 1) {
          all.insert(all.end(), out[0].begin(), out[0].end());
          return;
        }
        const std::vector<T> joined = join_in_parts(out, [](std::size_t k, auto&& g) { C::parallel_for(k, g); });
        all.insert(all.end(), joined.begin(), joined.end());
      });
  return all;
}

}  // namespace metrica
