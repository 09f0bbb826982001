// Conversion between the file content (io::MeshData) and the Mesh.
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>
#include <metrica/surface_angles.hpp>

#include <string>

namespace metrica {

struct BuildOptions {
  // Surface id given to boundary faces that no input triangle covers;
  // 0 means one more than the largest id in the input.
  SurfaceId default_surface_id = 0;
  // When set, an input with triangles must cover the whole boundary with
  // them (a boundary face without one is an InputError: a boundary given
  // in part is more likely a mistake than a choice). An input without any
  // boundary triangle is split by angle (below).
  bool require_boundary_triangles = false;
  // Surfaces and ridges by angle (surface_angles.hpp): the boundary faces
  // no triangle covers, or a boundary that is one surface id, are split
  // into surfaces at the edges sharper than ridge_angle degrees (180 or
  // more: never), unless the input has CAD association records (its ids
  // are then a model's surfaces).
  double ridge_angle = kDefaultRidgeAngle;
  // Every surface is split so, not only those.
  bool split_every_surface = false;
  // A piece of a larger mesh measured alone: its boundary faces have no
  // triangles by design, so no warning says so.
  bool untagged_expected = false;
  // Name used in messages (usually the file).
  std::string source = "mesh";
};

// Builds the Mesh from raw arrays: adjacency by matching faces through
// the vertex-to-tet incidence, boundary faces tagged from the triangles,
// internal surfaces from the triangles on faces with a tet on both sides
// and from the faces between regions (tet refs), ridges and corners
// classified. Throws InputError on inverted or
// degenerate tets, faces shared by more than two tets, or triangles that
// are not faces of the mesh. If every tet is negatively oriented (another
// tool's convention) all are reoriented, with a warning.
Mesh build_mesh(const io::MeshData& data, const BuildOptions& options = {});

// The file content of a Mesh: live entities renumbered densely, boundary
// faces as Triangles oriented outwards with their surface id (and each
// internal-surface face once, with its id), ridge edges
// as Edges listed in Ridges, corners and required vertices.
io::MeshData extract_mesh_data(const Mesh& mesh);

}  // namespace metrica
