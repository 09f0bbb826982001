// Work lists in vertex order without a comparison sort. The passes list
// what to try by id (the vertices of poor tets, the edges of changed
// tets), with repeats, and want each once in vertex order: after
// compact() that is space order, the seed's buckets for locality. Ids are
// bounded by the mesh's capacity, so a bucket per vertex orders them in
// linear time; std::sort of these lists was 5% of an adaptation.
#pragma once

#include <metrica/ids.hpp>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace metrica {

// Makes `ids` (each below `capacity`) sorted and free of repeats.
inline void sort_unique_ids(std::vector<std::uint32_t>& ids, std::size_t capacity) {
  std::vector<std::uint8_t> marked(capacity, 0);
  for (std::uint32_t id : ids) marked[id] = 1;
  ids.clear();
  for (std::size_t i = 0; i < capacity; ++i)
    if (marked[i] != 0) ids.push_back(static_cast<std::uint32_t>(i));
}

// Sorts `items` by key(item) (a 64-bit key whose upper 32 bits are a
// vertex id below `capacity`, as edge_key's lower vertex) and keeps one
// item per key. In place: an American flag sort on the vertex (each swap
// puts one item in its bucket), then each bucket, a handful of items,
// sorted by insertion. Which of the items with one key is kept is fixed
// by the input order, so a run is reproducible.
template <class Item, class Key>
void sort_unique_by_vertex_key(std::vector<Item>& items, std::size_t capacity, Key key) {
  auto bucket = [&](const Item& x) { return static_cast<std::size_t>(key(x) >> 32); };
  std::vector<std::uint32_t> start(capacity + 1, 0);
  for (const Item& x : items) ++start[bucket(x) + 1];
  for (std::size_t v = 0; v < capacity; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  for (std::size_t v = 0; v < capacity; ++v)
    while (next[v] < start[v + 1]) {
      Item& x = items[next[v]];
      const std::size_t b = bucket(x);
      if (b == v) {
        ++next[v];
      } else {
        std::swap(x, items[next[b]++]);
      }
    }
  std::size_t out = 0;
  for (std::size_t v = 0; v < capacity; ++v) {
    const std::size_t first = start[v], last = start[v + 1];
    for (std::size_t i = first + 1; i < last; ++i)
      for (std::size_t j = i; j > first && key(items[j]) < key(items[j - 1]); --j) std::swap(items[j], items[j - 1]);
    for (std::size_t i = first; i < last; ++i)
      if (i == first || key(items[i]) != key(items[i - 1])) items[out++] = items[i];
  }
  items.resize(out);
}

}  // namespace metrica
