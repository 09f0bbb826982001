// SU2 native mesh (.su2): tets, points and one marker per surface id (the
// marker tag is the id itself, e.g. MARKER_TAG= 3), for the SU2 solver.
#pragma once

#include <metrica/io/mesh_data.hpp>

#include <string>

namespace metrica::io {

std::string format_su2(const MeshData& mesh);
void write_su2(const std::string& path, const MeshData& mesh);

// Reads tets (NELEM=, VTK type 10) and marker triangles (type 5): a marker
// whose tag is a positive number has that surface id, a named one gets an
// id from 1001 on, in file order (logged). Regions are 0 (.su2 has none).
// IoError for other element types or a malformed file.
MeshData read_su2(const std::string& path);
// The same from the file's text (`path` names it in messages).
MeshData parse_su2(std::string text, const std::string& path);

}  // namespace metrica::io
