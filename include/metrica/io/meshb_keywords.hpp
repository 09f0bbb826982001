// libMeshb keyword codes and names Metrica reads and writes (the codes are
// fixed by the format; see libMeshb's GmfKwdFmt table). Internal header.
#pragma once

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

// Sizes of one real, one integer and one keyword offset in a binary file.
struct Widths {
  int real;
  int integer;
  int offset;
  explicit Widths(int version)
      : real(version == 1 ? 4 : 8), integer(version == 4 ? 8 : 4), offset(version >= 3 ? 8 : 4) {}
};

}  // namespace metrica::io::meshb
