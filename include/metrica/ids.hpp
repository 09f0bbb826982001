// Ids and small value types shared by every component.
//
// Entities live in flat arrays and are named by 32-bit ids: half the memory
// traffic of 64-bit indices, and 4e9 entities is far beyond a shared-memory
// run (a 1e9-tet mesh needs ~100 GB).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
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

// The largest surface id a mesh holds, and the most tets (both bounded by
// FaceRef's one word).
inline constexpr SurfaceId kMaxSurfaceId = (1 << 28) - 1;
inline constexpr std::size_t kMaxTets = 0x3C000000;  // 1,006,632,960

// A face of a tet seen from the other side: the neighbouring tet and its
// local face index (the face opposite that vertex), packed as 4*tet + face
// in one word so that an adjacency slot is a single atomic-sized value;
// or, where the face has no neighbour, its surface id s (0 for none yet)
// as kNoId - s. One word for both: interior faces have no surface id
// and boundary faces no neighbour, so a second array of surface ids per
// tet face (16 bytes per tet) held zeros on all but a few faces.
class FaceRef {
 public:
  constexpr FaceRef() = default;
  constexpr FaceRef(TetId tet, int face) : code_(tet * 4u + static_cast<std::uint32_t>(face)) {}
  // No neighbour: a face without one, of surface `id` (0..kMaxSurfaceId).
  static constexpr FaceRef none() { return FaceRef(); }
  static constexpr FaceRef boundary(SurfaceId id) {
    FaceRef f;
    f.code_ = kNoId - static_cast<std::uint32_t>(id);
    return f;
  }

  constexpr TetId tet() const { return code_ >> 2; }
  constexpr int face() const { return static_cast<int>(code_ & 3u); }
  constexpr bool valid() const { return code_ < kFirstBoundary; }
  // The surface id of a face without a neighbour; 0 for a neighbour.
  constexpr SurfaceId surface() const { return valid() ? 0 : static_cast<SurfaceId>(kNoId - code_); }
  constexpr std::uint32_t code() const { return code_; }
  friend constexpr bool operator==(FaceRef, FaceRef) = default;

 private:
  static constexpr std::uint32_t kFirstBoundary = kNoId - static_cast<std::uint32_t>(kMaxSurfaceId);
  static_assert(4 * kMaxTets <= kFirstBoundary);
  std::uint32_t code_ = kNoId;
};

}  // namespace metrica
