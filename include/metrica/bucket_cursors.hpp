// The counting half of a counting sort in parts: what the edge buckets
// (operators/edge_buckets.hpp) and compaction's order of the tets
// (compact.cpp) both start from. Items [0, n) are cut into `parts`
// slices, one per thread:
//   1. each part counts its items' keys (its own counters);
//   2. bucket starts by a prefix sum over (key, part): each part sums a
//      slice of keys, the slices' bases by a short prefix sum, then each
//      slice turns its counters into cursors.
// Bucket k then holds part 0's entries of key k, then part 1's, so that a
// scatter of each part's items in order through its cursors gives the
// order of one thread going through the items, for any number of parts.
// Linear, no comparison sort; parts x keys 4-byte counters.
#pragma once

#include <metrica/mesh_array.hpp>
#include <metrica/part_runner.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace metrica {

// keys_of(i, add) calls add(k) for each key k < `keys` item i brings (an
// entry each). Afterwards cursor[p * keys + k] is where part p's first
// entry of key k goes and start[k] where bucket k begins (start[keys]:
// the total, which is returned). run(m, f) runs f(0) .. f(m - 1),
// possibly concurrently (a PartRunner, or a policy's parallel_for).
// Neither array is zeroed by its resize: each part writes its own slice
// first (the pages are touched by the thread that uses them).
template <class KeysOf, class Run>
std::size_t bucket_cursors(std::size_t n, std::size_t keys, std::size_t parts, KeysOf&& keys_of, Run&& run,
                           MeshArray<std::uint32_t>& cursor, MeshArray<std::uint32_t>& start) {
  parts = std::max<std::size_t>(parts, 1);
  cursor.resize(parts * keys);
  run(parts, [&](std::size_t p) {
    std::uint32_t* count = cursor.data() + p * keys;
    std::fill(count, count + keys, 0u);
    const auto [first, last] = part_slice(n, parts, p);
    for (std::size_t i = first; i < last; ++i) keys_of(i, [count](std::size_t k) { ++count[k]; });
  });
  start.resize(keys + 1);
  std::vector<std::uint64_t> base(parts + 1, 0);
  run(parts, [&](std::size_t q) {
    std::uint64_t sum = 0;
    const auto [lo, hi] = part_slice(keys, parts, q);
    for (std::size_t p = 0; p < parts; ++p) {
      const std::uint32_t* count = cursor.data() + p * keys;
      for (std::size_t k = lo; k < hi; ++k) sum += count[k];
    }
    base[q + 1] = sum;
  });
  for (std::size_t q = 0; q < parts; ++q) base[q + 1] += base[q];
  const std::uint64_t total = base[parts];
  if (total > std::uint64_t{0xfffffffe}) throw std::length_error("bucket_cursors: more than 2^32 - 2 entries");
  run(parts, [&](std::size_t q) {
    auto at = static_cast<std::uint32_t>(base[q]);
    const auto [lo, hi] = part_slice(keys, parts, q);
    for (std::size_t k = lo; k < hi; ++k) {
      start[k] = at;
      for (std::size_t p = 0; p < parts; ++p) {
        std::uint32_t& c = cursor[p * keys + k];
        const std::uint32_t m = c;
        c = at;
        at += m;
      }
    }
  });
  start[keys] = static_cast<std::uint32_t>(total);
  return static_cast<std::size_t>(total);
}

}  // namespace metrica
