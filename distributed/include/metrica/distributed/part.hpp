// One rank's part of a distributed mesh: its tets, the vertices they use
// and the boundary and internal-surface triangles on their faces. Each
// vertex has a 64-bit global id; the tets name their vertices by local
// index (their places in the part's arrays: every pass over the tets
// reads them directly), the triangles and the faces between parts by
// global id. A vertex on the boundary between two parts is held by both
// with the same global id and coordinates; the faces between parts are
// listed with the rank across them.
#pragma once

#include <metrica/ids.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace metrica::distributed {

using GlobalId = std::int64_t;
// A face by its three global vertex ids, sorted.
using FaceKey = std::array<GlobalId, 3>;

inline FaceKey face_key(GlobalId a, GlobalId b, GlobalId c) {
  FaceKey k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// The faces of a tet, each by the three corners it keeps.
inline constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

// Whether sorting the triangle (a, b, c) into its key turns it over.
inline bool turned_over(const std::array<GlobalId, 3>& t) {
  return ((t[0] > t[1]) + (t[0] > t[2]) + (t[1] > t[2])) % 2 == 1;
}
inline FaceKey face_key(const std::array<GlobalId, 3>& t) { return face_key(t[0], t[1], t[2]); }
// The triangle of `key` with the orientation turned_over gave.
inline std::array<GlobalId, 3> oriented(const FaceKey& key, bool turned) {
  return turned ? std::array<GlobalId, 3>{key[0], key[2], key[1]} : key;
}

// A point as plain doubles, for messages (Eigen's types are not
// trivially copyable).
using Coords = std::array<double, 3>;
inline Coords coords(const Point& p) { return {p.x(), p.y(), p.z()}; }
inline Point point(const Coords& c) { return {c[0], c[1], c[2]}; }

// The rank that pairs the tets of a face, or holds a vertex's rendezvous:
// a mix of the ids, so that faces spread evenly over the ranks.
inline std::uint64_t mix(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}
inline int owner_of(std::uint64_t id, int ranks) { return int(mix(id) % std::uint64_t(ranks)); }
inline std::uint64_t face_hash(const FaceKey& k) {
  return mix(std::uint64_t(k[0]) * 0x9e3779b97f4a7c15ULL ^ std::uint64_t(k[1]) * 0xbf58476d1ce4e5b9ULL ^
             std::uint64_t(k[2]));
}
inline int owner_of(const FaceKey& k, int ranks) { return int(face_hash(k) % std::uint64_t(ranks)); }

// A tet by the local indices of its vertices.
using LocalTet = std::array<std::uint32_t, 4>;

struct Part {
  std::vector<GlobalId> vertex_ids;  // global id of each local vertex
  std::vector<Point> points;
  std::vector<Sym6> metrics;  // per local vertex; empty with an analytic metric
  // Per local vertex, its CAD entity and parameters (invalid inside the
  // domain); empty without a model.
  std::vector<GeoParam> geo;
  std::vector<LocalTet> tets;  // local vertex indices
  std::vector<int> tet_refs;
  // Per tet, whether the round adapts it (empty: all); travels with it.
  std::vector<std::uint8_t> focus;
  std::vector<std::array<GlobalId, 3>> triangles;  // oriented as read or written
  std::vector<int> triangle_refs;
  // The faces this part shares with another part, and that part's rank.
  std::vector<FaceKey> shared_faces;  // sorted
  std::vector<int> shared_with;
  // Whether each triangle lies on a face of this part's tets (an internal
  // surface's on both sides' parts) and shared_faces lists every face
  // between ranks: so after a move, not as read in slices.
  bool faces_known = false;
};

// The entries i of v with keep[i], in order, in place (an empty v stays
// empty: a part without metrics or focus).
template <class T>
void keep_only(std::vector<T>& v, const std::vector<bool>& keep) {
  if (v.empty()) return;
  std::size_t w = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) v[w++] = v[i];
  v.resize(w);
}
// The part's tets (with refs and focus), vertices (with points, metrics
// and CAD parameters) or triangles (with refs) flagged in `keep`, in place.
inline void keep_tets(Part& part, const std::vector<bool>& keep) {
  keep_only(part.tets, keep);
  keep_only(part.tet_refs, keep);
  keep_only(part.focus, keep);
}
// The vertex records alone: the tets' indices are the caller's to renumber.
inline void keep_vertex_records(Part& part, const std::vector<bool>& keep) {
  keep_only(part.vertex_ids, keep);
  keep_only(part.points, keep);
  keep_only(part.metrics, keep);
  keep_only(part.geo, keep);
}
// The vertices the tets use must all be kept; their indices follow.
inline void keep_vertices(Part& part, const std::vector<bool>& keep) {
  std::vector<std::uint32_t> place(keep.size(), 0);
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < keep.size(); ++v)
    if (keep[v]) place[v] = next++;
  for (auto& t : part.tets)
    for (auto& v : t) v = place[v];
  keep_vertex_records(part, keep);
}

// The global ids of tet t's vertices; of a face of it (kTetFaces[f]) as a key.
inline std::array<GlobalId, 4> global_tet(const Part& part, std::size_t t) {
  const auto& l = part.tets[t];
  const auto& g = part.vertex_ids;
  return {g[l[0]], g[l[1]], g[l[2]], g[l[3]]};
}
inline FaceKey global_face(const Part& part, std::size_t t, int f) {
  const auto& l = part.tets[t];
  const auto& c = kTetFaces[f];
  const auto& g = part.vertex_ids;
  return face_key(g[l[std::size_t(c[0])]], g[l[std::size_t(c[1])]], g[l[std::size_t(c[2])]]);
}
inline void keep_triangles(Part& part, const std::vector<bool>& keep) {
  keep_only(part.triangles, keep);
  keep_only(part.triangle_refs, keep);
}

// The local index of each global id of `part`: an open-addressing table
// (linear probing, at most 2/3 full) of the ids and their places. Every
// pass over a part's tets looks up their vertices here; a binary search
// over the sorted ids took 14% of a rank's time at 1M tets on 2 ranks.
class VertexIndex {
 public:
  explicit VertexIndex(const std::vector<GlobalId>& ids);
  // Local index of id; -1 when the part does not hold it (the first place
  // when it holds it twice; negative ids are never held).
  std::int64_t find(GlobalId id) const {
    for (std::size_t s = slot(id);; s = (s + 1) & mask_) {
      if (keys_[s] == kEmpty) return -1;
      if (keys_[s] == id) return places_[s];
    }
  }

 private:
  static constexpr GlobalId kEmpty = -1;
  std::size_t slot(GlobalId id) const {
    // Fibonacci hashing: consecutive ids spread over the table.
    return std::size_t((std::uint64_t(id) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  std::vector<GlobalId> keys_;
  std::vector<std::uint32_t> places_;
  std::size_t mask_ = 0;
  int shift_ = 64;
};

}  // namespace metrica::distributed
