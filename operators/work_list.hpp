// Work lists in id order without a comparison sort. A pass lists what to
// try by id (the vertices of poor tets), with repeats, and wants each once
// in id order: after compact() that is space order, the seed's buckets
// for locality. Ids are bounded by the mesh's capacity, so marks order
// them in linear time (std::sort of smoothing's list was 1.5% of an
// adaptation).
#pragma once

#include <metrica/ids.hpp>

#include <cstdint>
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

}  // namespace metrica
