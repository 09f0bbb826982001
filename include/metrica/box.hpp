// Box meshes: an nx x ny x nz grid of hexes, each split into 6 tets.
//
// Every hex is cut along its main diagonal (Kuhn's subdivision), so the
// face diagonals of neighbouring hexes agree and the mesh is conforming.
// Surface ids follow the UGAWG cube: 1 x = xmin, 2 x = xmax, 3 y = ymin,
// 4 y = ymax, 5 z = zmin, 6 z = zmax. Vertices are numbered x fastest.
// n = 3 gives the 4x4x4-vertex UGAWG start mesh (64 vertices, 162 tets).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

namespace metrica {

struct BoxSpec {
  int nx = 3, ny = 3, nz = 3;  // hexes per direction
  Point lo = Point(0, 0, 0);
  Point hi = Point(1, 1, 1);
};

// InputError unless each count is in [1, 1000] (at most 600 million tets
// in all) and lo < hi in every direction, both corners finite and within
// +-kCoordinateLimit (input_checks.hpp).
void check_box_spec(const BoxSpec& spec);

io::MeshData box_mesh_data(const BoxSpec& spec);
Mesh make_box(const BoxSpec& spec);

}  // namespace metrica
