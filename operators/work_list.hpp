// Work lists in id order without a comparison sort. A pass lists what to
// try by id (the vertices of poor tets), with repeats, and wants each once
// in id order: after compact() that is space order, the seed's buckets
// for locality. Ids are bounded by the mesh's capacity, so marks order
// them in linear time (std::sort of smoothing's list was 1.5% of an
// adaptation).
#pragma once

#include <metrica/ids.hpp>
#include <metrica/tet_topology.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
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

// An edge and a tet that holds it (the tet is where a shell walk starts).
struct EdgeSeed {
  std::uint64_t key;  // edge_key(lower, higher)
  TetId tet;
};

// The distinct edges of `tets`, each with the first tet of `tets` that
// holds it, ordered by key (lower vertex, then higher): what sorting the
// 6 edges of every tet by key and keeping the first of each run gives.
// `vertices_of(t)` gives tet t's vertices, each below `capacity`. A
// counting sort on the lower vertex, then marks on the higher one within
// each bucket: linear time where std::sort of the 6 keys per tet (about
// five repeats of each edge) was 4% of an adaptation.
template <class VerticesOf>
void unique_edge_seeds(std::span<const TetId> tets, VerticesOf&& vertices_of, std::size_t capacity,
                       std::vector<EdgeSeed>& out) {
  std::vector<std::uint32_t> start(capacity + 1, 0);
  for (TetId t : tets) {
    const TetVertices& v = vertices_of(t);
    for (const auto& e : kEdgeVertex) ++start[std::min(v[e[0]], v[e[1]]) + 1];
  }
  for (std::size_t i = 0; i < capacity; ++i) start[i + 1] += start[i];
  out.resize(start[capacity]);
  {
    std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (TetId t : tets) {
      const TetVertices& v = vertices_of(t);
      for (const auto& e : kEdgeVertex) {
        const VertexId a = v[e[0]], b = v[e[1]];
        out[cursor[std::min(a, b)]++] = {edge_key(a, b), t};
      }
    }
  }
  // In place: the kept entries of bucket a move down to `w` <= their slot.
  // last[b] == a: edge ab already kept.
  std::vector<VertexId> last(capacity, kNoId);
  std::size_t w = 0;
  for (std::size_t a = 0; a < capacity; ++a) {
    const std::size_t first = w;
    for (std::uint32_t i = start[a]; i < start[a + 1]; ++i) {
      const auto b = static_cast<VertexId>(out[i].key & 0xffffffffu);
      if (last[b] == static_cast<VertexId>(a)) continue;
      last[b] = static_cast<VertexId>(a);
      out[w++] = out[i];
    }
    // A handful of edges per vertex: insertion sort by the higher end.
    for (std::size_t i = first + 1; i < w; ++i)
      for (std::size_t j = i; j > first && out[j].key < out[j - 1].key; --j) std::swap(out[j], out[j - 1]);
  }
  out.resize(w);
}

}  // namespace metrica
