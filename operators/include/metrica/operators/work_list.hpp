// Work lists in id order without a comparison sort: a pass lists what to
// try by id and wants each once in id order (after compact() that is
// space order, the seed's buckets for locality). Ids are bounded by the
// mesh's capacity, so marks or buckets order them in linear time
// (std::sort of smoothing's list was 1.5% of an adaptation; smoothing
// now lists its vertices from marks, smooth.hpp).
#pragma once

#include <metrica/ids.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace metrica {

// An edge and a tet that holds it (the tet is where a shell walk starts).
struct EdgeSeed {
  std::uint64_t key;  // edge_key(lower, higher)
  TetId tet;
};

// The distinct edges of `tets`, each with the first tet of `tets` that
// holds it, ordered by key (lower vertex, then higher): what sorting the
// 6 edges of every tet by key and keeping the first of each run gives.
// `vertices_of(t)` gives tet t's vertices, each below `capacity`. Edge
// buckets (edge_buckets.hpp) on C's threads, the same list for any number
// of threads: linear time where std::sort of the 6 keys per tet (about
// five repeats of each edge) was 4% of an adaptation.
template <class C = Serial, class VerticesOf, class Out>
void unique_edge_seeds(std::span<const TetId> tets, VerticesOf&& vertices_of, std::size_t capacity, Out& out) {
  const std::size_t parts = sweep_parts<C>(tets.size());
  // Each part writes its edges straight into `out`, from its offset on,
  // `out` sized once (no growth, no join).
  struct alignas(64) Cursor {
    std::size_t at = 0;
  };
  std::vector<Cursor> cursor(parts);
  out.clear();
  for_each_edge_bucket<C, UpperTet>(
      parts, tets.size(), [&](std::size_t i) { return tets[i]; }, vertices_of, capacity, true,
      [&](std::size_t p, VertexId a, std::span<const UpperTet> kept) {
        std::size_t& at = cursor[p].at;
        for (const UpperTet& x : kept) out[at++] = EdgeSeed{edge_key(a, x.upper), x.tet};
      },
      [&](std::span<const std::size_t> edges_in) {
        std::size_t total = 0;
        for (std::size_t p = 0; p < parts; ++p) {
          cursor[p].at = total;
          total += edges_in[p];
        }
        out.resize(total);
      });
}

}  // namespace metrica
