// The libMeshb layout Metrica reads and writes: keyword codes and names
// (fixed by the format; see libMeshb's GmfKwdFmt table), the widths of a
// version's numbers and the bytes of each keyword's rows. The readers and
// writers of one process and those of the ranks under MPI share it.
// Internal header.
#pragma once

#include <cstdint>
#include <limits>
#include <string_view>

namespace metrica::io::meshb {

enum Keyword : int {
  kVersion = 1,
  kDimension = 3,
  kVertices = 4,
  kEdges = 5,
  kTriangles = 6,
  kTetrahedra = 8,
  kCorners = 13,
  kRidges = 14,
  kRequiredVertices = 15,
  kRequiredEdges = 16,
  kRequiredTriangles = 17,
  kVerticesOnGeometricVertices = 40,
  kVerticesOnGeometricEdges = 41,
  kVerticesOnGeometricTriangles = 42,
  kEnd = 54,
  kSolAtVertices = 62,
};

inline constexpr int kMagic = 1;
inline constexpr int kMagicSwapped = 0x01000000;

constexpr std::string_view keyword_name(int code) {
  switch (code) {
    case kVersion: return "MeshVersionFormatted";
    case kDimension: return "Dimension";
    case kVertices: return "Vertices";
    case kEdges: return "Edges";
    case kTriangles: return "Triangles";
    case kTetrahedra: return "Tetrahedra";
    case kCorners: return "Corners";
    case kRidges: return "Ridges";
    case kRequiredVertices: return "RequiredVertices";
    case kRequiredEdges: return "RequiredEdges";
    case kRequiredTriangles: return "RequiredTriangles";
    case kVerticesOnGeometricVertices: return "VerticesOnGeometricVertices";
    case kVerticesOnGeometricEdges: return "VerticesOnGeometricEdges";
    case kVerticesOnGeometricTriangles: return "VerticesOnGeometricTriangles";
    case kEnd: return "End";
    case kSolAtVertices: return "SolAtVertices";
    default: return "";
  }
}

inline int keyword_code(std::string_view name) {
  for (int code : {kVersion, kDimension, kVertices, kEdges, kTriangles, kTetrahedra, kCorners, kRidges,
                   kRequiredVertices, kRequiredEdges, kRequiredTriangles, kVerticesOnGeometricVertices,
                   kVerticesOnGeometricEdges, kVerticesOnGeometricTriangles, kEnd, kSolAtVertices})
    if (keyword_name(code) == name) return code;
  return 0;
}

// Sizes of one real, one integer and one keyword offset in a binary file,
// and of the rows built from them.
struct Widths {
  int real;
  int integer;
  int offset;
  explicit Widths(int version)
      : real(version == 1 ? 4 : 8), integer(version == 4 ? 8 : 4), offset(version >= 3 ? 8 : 4) {}
  // A keyword's code, the offset of the next keyword, its row count.
  std::uint64_t keyword_head() const { return 4 + std::uint64_t(offset) + std::uint64_t(integer); }
  // x y z ref; v1 v2 v3 ref; v1 v2 v3 v4 ref.
  std::uint64_t vertex_row() const { return 3 * std::uint64_t(real) + std::uint64_t(integer); }
  std::uint64_t triangle_row() const { return 4 * std::uint64_t(integer); }
  std::uint64_t tet_row() const { return 5 * std::uint64_t(integer); }
  // VerticesOnGeometric{Vertices, Edges, Triangles} (dim 0, 1, 2): the
  // vertex and its entity, then t and dist on a curve, u, v and dist on a
  // surface.
  std::uint64_t on_geometry_row(int dim) const {
    return 2 * std::uint64_t(integer) + std::uint64_t(dim == 0 ? 0 : dim + 1) * std::uint64_t(real);
  }
  // SolAtVertices of one symmetric matrix field: the keyword's head, the
  // field count and its type, then six reals a vertex.
  std::uint64_t one_field_sol_head() const { return keyword_head() + 8; }
  std::uint64_t sym_matrix_row() const { return 6 * std::uint64_t(real); }
};

// The largest file a version 1 or 2 binary file's 32-bit offsets reach,
// and the largest row count of versions 1 to 3's 32-bit integers.
inline constexpr std::uint64_t kMaxBytesOfShortOffsets = std::uint64_t(std::numeric_limits<std::int32_t>::max());
inline constexpr std::uint64_t kMaxRowsOfShortIntegers = std::uint64_t(std::numeric_limits<std::int32_t>::max());

}  // namespace metrica::io::meshb
