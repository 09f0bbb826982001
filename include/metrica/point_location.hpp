// Point location by walking and the transfer of a vertex field from one
// mesh to another (a solver restarting on the adapted mesh from its
// previous solution, seed section 5.1).
//
// The walk (visibility walk): from a tet, compute the barycentric
// coordinates of the point; if one is negative, step across the face
// opposite the most negative one. On a valid mesh of a convex region the
// walk ends in the containing tet; a point outside the domain (a curved
// boundary discretised differently by the two meshes) stops at a boundary
// face, and the closest tet seen is used with its coordinates clamped to
// the tet. After Mesh::compact the points of the target mesh come in space
// order, so each walk starts from the tet where the previous one ended.
// Around holes and re-entrant corners PointLocator takes over.
#pragma once

#include <metrica/mesh.hpp>

#include <array>
#include <vector>

namespace metrica {

struct Location {
  TetId tet = kNoId;
  std::array<double, 4> bary{};  // clamped to [0, 1], summing to 1
  bool inside = false;           // false: the point lies outside the mesh (bary clamped)
  int steps = 0;
};

// The tet holding p, walking from `start` (any live tet; kNoId: the first).
Location locate(const Mesh& mesh, const Point& p, TetId start = kNoId);

// Point location in a domain of any shape. A walk cannot go around a hole
// (the body in a flow) or a re-entrant corner: it stops at the boundary
// face in the way. The locator then walks again from the tets of the
// point's cell and of the cells around it in a grid of tet centroids
// (about two tets per cell), and when none ends in a tet holding the point
// and the nearest stop is farther than a cell from it, scans every tet. A
// point outside the mesh keeps the best tet found, coordinates clamped
// (inside = false).
class PointLocator {
 public:
  explicit PointLocator(const Mesh& mesh);
  Location locate(const Point& p, TetId hint = kNoId) const;

 private:
  // Tets with their centroid near p: in its cell or the cells around it.
  void grid_tets(const Point& p, std::vector<TetId>& out) const;
  const Mesh& mesh_;
  Point lo_ = Point::Zero();
  Eigen::Vector3d cell_ = Eigen::Vector3d::Ones();
  std::array<int, 3> n_{1, 1, 1};
  std::vector<TetId> cells_;  // one tet whose centroid lies in the cell, or kNoId
  double round_off_ = 0.0;    // distance below which a clamped point is the point
};

// The P1 interpolant of `values` (by vertex id of `from`) at every vertex of
// `to`; the result is indexed by vertex id of `to`. InputError when sizes
// do not match. `outside`, when given, counts the target vertices that lay
// outside `from` (clamped).
std::vector<double> interpolate_vertex_field(const Mesh& from, const std::vector<double>& values, const Mesh& to,
                                             std::size_t* outside = nullptr);

// The same for `width` values per vertex (vertex-major: the values of vertex
// v at [v * width, (v + 1) * width)), each interpolated on its own: every
// field of a solution file (velocity components, pressure) in one walk.
std::vector<double> interpolate_vertex_values(const Mesh& from, const std::vector<double>& values, int width,
                                              const Mesh& to, std::size_t* outside = nullptr);

}  // namespace metrica
