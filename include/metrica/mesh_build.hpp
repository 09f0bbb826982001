// Conversion between the file content (io::MeshData) and the Mesh.
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

#include <string>

namespace metrica {

struct BuildOptions {
  // Surface id given to boundary faces that no input triangle covers;
  // 0 means one more than the largest id in the input.
  SurfaceId default_surface_id = 0;
  // When set, a boundary face that no input triangle covers is an
  // InputError: the adaptation takes its surfaces and ridges from the
  // triangles' ids, and a boundary without them would lose its corners.
  bool require_boundary_triangles = false;
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
