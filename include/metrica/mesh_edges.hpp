// The unique edges of a mesh, for loops over edges (gradation, quality
// reports, point creation by edges). A snapshot, sorted by (low, high) id.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/mesh_array.hpp>
#include <metrica/part_runner.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace metrica {

// The tets' edges bucketed by lower end (with repeats), counted in parts:
// the tets cut into `parts` slices (part_slice), count[p * vertex_capacity
// + a] of part p's edges with lower end a; bucket a is [start[a],
// start[a + 1]) of all parts' entries, start[vertex_capacity] in all.
// Counted once, filled a range of lower ends at a time (each part scans
// its own slice of the tets), so the fills run on the sweep's threads.
struct LowerEdgeCounts {
  // The parts of the fills, at most this many: each holds a counter per
  // vertex id.
  static constexpr std::size_t kMaxParts = 8;
  std::size_t parts = 1;
  MeshArray<std::uint32_t> count;
  std::vector<std::uint32_t> start;
};
void count_edges_by_lower_vertex(const Mesh& mesh, const PartRunner& run, LowerEdgeCounts& counts);

// The higher ends of the edges whose lower end is in [lo, hi), bucketed:
// bucket a is upper[start[a] - start[lo] .. start[a + 1] - start[lo]),
// each bucket in the order of the tets for any number of parts (part p's
// entries after part p - 1's). Each range once per count: it turns the
// range's counts into cursors.
void edges_by_lower_vertex(const Mesh& mesh, LowerEdgeCounts& counts, VertexId lo, VertexId hi, const PartRunner& run,
                           std::vector<VertexId>& upper);

// How many ranges of lower ends a listing of `entries` edge bucket
// entries (a vertex id each, 6 per tet) is cut into: one per 4 MiB of
// them, at most max_ranges (a range costs a scan of the tets). Listed at
// once, a mesh's edges were among an adaptation's memory peaks; by 32 MiB
// they were still a third of the mesh's arrays at 1M tets.
std::size_t edge_ranges(std::size_t entries, std::size_t max_ranges);

// The ranges of for_each_unique_edge: edge_ranges, at most 8.
inline std::size_t unique_edge_ranges(std::size_t entries) { return edge_ranges(entries, 8); }

// The vertex blocks of for_each_unique_edge on several threads: the calls
// for the lower ends in one block come from one thread, in order.
inline constexpr std::size_t kEdgeBlockVertices = 4096;

// f(a, b) for each edge, a < b, in the order of unique_edges, without
// holding the list: the buckets of one range of lower ends at a time
// (unique_edge_ranges), so a report over every edge of a large mesh holds
// an eighth of its edges' entries at most, not 24 bytes per tet. With a
// runner, the blocks of lower ends (a / kEdgeBlockVertices) of a range
// are shared among its parts: f is then called concurrently for edges in
// different blocks, and a caller that keeps one sum per block gets the
// same sums for any runner. `ranges` > 0 sets their number (tests).
template <class F>
void for_each_unique_edge(const Mesh& mesh, F&& f, const PartRunner& run = {}, std::size_t ranges = 0) {
  LowerEdgeCounts counts;
  count_edges_by_lower_vertex(mesh, run, counts);
  const std::vector<std::uint32_t>& start = counts.start;
  const auto nv = static_cast<VertexId>(mesh.vertex_capacity());
  const std::size_t total = start[nv];
  if (ranges == 0) ranges = unique_edge_ranges(total);
  std::vector<VertexId> upper;
  VertexId lo = 0;
  for (std::size_t r = 0; r < ranges && lo < nv; ++r) {
    // The range ends where the buckets reach its share of the entries.
    const auto target = static_cast<std::uint32_t>(total * (r + 1) / ranges);
    const VertexId hi =
        r + 1 == ranges ? nv
                        : static_cast<VertexId>(std::max<std::ptrdiff_t>(
                              lo, std::lower_bound(start.begin() + lo, start.begin() + nv, target) - start.begin()));
    if (hi == lo) continue;
    edges_by_lower_vertex(mesh, counts, lo, hi, run, upper);
    const std::size_t first_block = lo / kEdgeBlockVertices;
    const std::size_t blocks = (hi - 1) / kEdgeBlockVertices + 1 - first_block;
    const std::size_t parts = std::clamp<std::size_t>(run.parts, 1, blocks);
    run(parts, [&](std::size_t p) {
      const auto [b0, b1] = part_slice(blocks, parts, p);
      const auto from = static_cast<VertexId>(std::max<std::size_t>(lo, (first_block + b0) * kEdgeBlockVertices));
      const auto to = static_cast<VertexId>(std::min<std::size_t>(hi, (first_block + b1) * kEdgeBlockVertices));
      for (VertexId a = from; a < to; ++a) {
        const auto first = upper.begin() + (start[a] - start[lo]), last = upper.begin() + (start[a + 1] - start[lo]);
        std::sort(first, last);
        for (auto it = first; it != last; ++it)
          if (it == first || *it != *(it - 1)) f(a, *it);
      }
    });
    lo = hi;
  }
}

std::vector<EdgeVertices> unique_edges(const Mesh& mesh);
// (The operators' passes build their edge lists on their policy's threads:
// operators/edge_buckets.hpp.)

}  // namespace metrica
