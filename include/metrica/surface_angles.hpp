// Surfaces and ridges of a boundary given without them: a mesh of points
// and tets only, or one surface id for the whole boundary. Its faces are
// split into surfaces at the edges where the faces' normals turn by more
// than a ridge angle (Mmg's -ar, 45 degrees by default); those edges are
// ridges, and classify() finds the corners where ridges meet. Without
// this, the adaptation sees one smooth surface and cuts the solid's edges.
#pragma once

#include <metrica/mesh.hpp>

#include <span>

namespace metrica {

inline constexpr double kDefaultRidgeAngle = 45.0;
// A ridge angle that splits nothing: the surfaces as the input gives them.
inline constexpr double kNoRidgeSplit = 180.0;

struct AngleSplit {
  std::size_t surfaces = 0;     // surfaces the split ids became
  std::size_t sharp_edges = 0;  // edges above the angle (ridges)
};

// Splits the outer boundary faces of the surface ids `ids` into the
// pieces that faces of one id make when joined across edges of at most
// `degrees` (an edge on more than two boundary faces is never crossed).
// The piece with the face of lowest (tet, face) keeps its id, the others
// take new ids above the mesh's largest; every sharp edge becomes a
// feature edge (a ridge even where it ends inside a surface). Then
// classifies the mesh. `degrees` >= 180 splits nothing.
AngleSplit split_surfaces_at_angle(Mesh& mesh, double degrees, std::span<const SurfaceId> ids);

}  // namespace metrica
