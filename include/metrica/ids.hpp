// Ids and small value types shared by every component.
//
// Entities live in flat arrays and are named by 32-bit ids: half the memory
// traffic of 64-bit indices, and 4e9 entities is far beyond a shared-memory
// run (a 1e9-tet mesh needs ~100 GB).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>

namespace metrica {

using VertexId = std::uint32_t;
using TetId = std::uint32_t;
// Surface id of a boundary face (> 0), 0 for an interior face.
using SurfaceId = std::int32_t;

inline constexpr std::uint32_t kNoId = std::numeric_limits<std::uint32_t>::max();

using Point = Eigen::Vector3d;

// A symmetric 3x3 tensor stored as 6 numbers in libMeshb order
// (xx, xy, yy, xz, yz, zz).
using Sym6 = std::array<double, 6>;

// Where a boundary vertex lies on the geometric model: the entity
// (dimension 0 model vertex, 1 curve, 2 surface; -1 none) with its tag and
// its parameters there (t = u on a curve, (u, v) on a surface).
struct GeoParam {
  std::int32_t tag = 0;
  std::int8_t dim = -1;
  double u = 0.0, v = 0.0;
  bool valid() const { return dim >= 0; }
  friend bool operator==(const GeoParam&, const GeoParam&) = default;
};

using TetVertices = std::array<VertexId, 4>;
using TriangleVertices = std::array<VertexId, 3>;
using EdgeVertices = std::array<VertexId, 2>;

// A face of a tet: the tet and its local face index (the face opposite that
// vertex), packed as 4*tet + face in one word so that an adjacency slot is
// a single atomic-sized value.
class FaceRef {
 public:
  constexpr FaceRef() = default;
  constexpr FaceRef(TetId tet, int face) : code_(tet * 4u + static_cast<std::uint32_t>(face)) {}
  static constexpr FaceRef none() { return FaceRef(); }

  constexpr TetId tet() const { return code_ >> 2; }
  constexpr int face() const { return static_cast<int>(code_ & 3u); }
  constexpr bool valid() const { return code_ != kNoId; }
  constexpr std::uint32_t code() const { return code_; }
  friend constexpr bool operator==(FaceRef, FaceRef) = default;

 private:
  std::uint32_t code_ = kNoId;
};

}  // namespace metrica
