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

// Step 1: count[p * keys + k] = how many entries of key k part p's items
// bring, where keys_of(i, add) calls add(k) for each key k < `keys` item
// i brings (an entry each) and run(m, f) runs f(0) .. f(m - 1), possibly
// concurrently (a PartRunner, or a policy's parallel_for). The array is
// not zeroed by its resize: each part writes its own slice first (the
// pages are touched by the thread that uses them).
template <class KeysOf, class Run>
void count_keys(std::size_t n, std::size_t keys, std::size_t parts, KeysOf&& keys_of, Run&& run,
                MeshArray<std::uint32_t>& count) {
  parts = std::max<std::size_t>(parts, 1);
  count.resize(parts * keys);
  run(parts, [&](std::size_t p) {
    std::uint32_t* c = count.data() + p * keys;
    std::fill(c, c + keys, 0u);
    const auto [first, last] = part_slice(n, parts, p);
    for (std::size_t i = first; i < last; ++i) keys_of(i, [c](std::size_t k) { ++c[k]; });
  });
}

// Step 2, for the keys [lo, hi) of step 1's counts (of `keys` keys), in
// place: count[p * keys + k] becomes where part p's first entry of key k
// goes and start[k - lo] where bucket k begins, buckets laid out from 0
// (start[hi - lo]: their total, which is returned). Other keys' counts
// are left as they were, so the keys can be taken a range at a time.
template <class Run>
std::size_t cursors_of_counts(std::size_t keys, std::size_t lo, std::size_t hi, std::size_t parts, Run&& run,
                              MeshArray<std::uint32_t>& count, MeshArray<std::uint32_t>& start) {
  parts = std::max<std::size_t>(parts, 1);
  const std::size_t width = hi - lo;
  start.resize(width + 1);
  std::vector<std::uint64_t> base(parts + 1, 0);
  run(parts, [&](std::size_t q) {
    std::uint64_t sum = 0;
    const auto [first, last] = part_slice(width, parts, q);
    for (std::size_t p = 0; p < parts; ++p) {
      const std::uint32_t* c = count.data() + p * keys + lo;
      for (std::size_t k = first; k < last; ++k) sum += c[k];
    }
    base[q + 1] = sum;
  });
  for (std::size_t q = 0; q < parts; ++q) base[q + 1] += base[q];
  const std::uint64_t total = base[parts];
  if (total > std::uint64_t{0xfffffffe}) throw std::length_error("bucket_cursors: more than 2^32 - 2 entries");
  run(parts, [&](std::size_t q) {
    auto at = static_cast<std::uint32_t>(base[q]);
    const auto [first, last] = part_slice(width, parts, q);
    for (std::size_t k = first; k < last; ++k) {
      start[k] = at;
      for (std::size_t p = 0; p < parts; ++p) {
        std::uint32_t& c = count[p * keys + lo + k];
        const std::uint32_t m = c;
        c = at;
        at += m;
      }
    }
  });
  start[width] = static_cast<std::uint32_t>(total);
  return static_cast<std::size_t>(total);
}

// Both steps for all keys: afterwards cursor[p * keys + k] is where part
// p's first entry of key k goes and start[k] where bucket k begins
// (start[keys]: the total, which is returned).
template <class KeysOf, class Run>
std::size_t bucket_cursors(std::size_t n, std::size_t keys, std::size_t parts, KeysOf&& keys_of, Run&& run,
                           MeshArray<std::uint32_t>& cursor, MeshArray<std::uint32_t>& start) {
  count_keys(n, keys, parts, keys_of, run, cursor);
  return cursors_of_counts(keys, 0, keys, parts, run, cursor, start);
}

}  // namespace metrica
