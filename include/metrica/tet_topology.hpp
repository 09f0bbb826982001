// Local numbering of a tetrahedron's faces and edges.
//
// Face i is the face opposite vertex i. Its vertices are listed so that,
// for a positively oriented tet (orient3d(v0,v1,v2,v3) > 0), the face's
// normal (b-a)x(c-a) points out of the tet: this is the orientation that
// boundary triangles are written with.
#pragma once

#include <metrica/ids.hpp>

#include <algorithm>
#include <array>

namespace metrica {

inline constexpr int kFaceVertex[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// The six edges of a tet as pairs of local vertices.
inline constexpr int kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

inline TriangleVertices face_vertices(const TetVertices& t, int face) {
  return {t[kFaceVertex[face][0]], t[kFaceVertex[face][1]], t[kFaceVertex[face][2]]};
}

inline TriangleVertices sorted(TriangleVertices f) {
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  if (f[1] > f[2]) std::swap(f[1], f[2]);
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  return f;
}

inline EdgeVertices sorted(EdgeVertices e) {
  if (e[0] > e[1]) std::swap(e[0], e[1]);
  return e;
}

// An undirected edge as one 64-bit key (smaller id in the high half), for
// hashing and sorting.
inline std::uint64_t edge_key(VertexId a, VertexId b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}
inline EdgeVertices edge_from_key(std::uint64_t key) {
  return {static_cast<VertexId>(key >> 32), static_cast<VertexId>(key & 0xffffffffu)};
}

// Local index of vertex v in tet t, or -1.
inline int local_index(const TetVertices& t, VertexId v) {
  for (int i = 0; i < 4; ++i)
    if (t[i] == v) return i;
  return -1;
}

}  // namespace metrica
