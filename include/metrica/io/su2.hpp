// SU2 native mesh (.su2): tets, points and one marker per surface id (the
// marker tag is the id itself, e.g. MARKER_TAG= 3), for the SU2 solver.
#pragma once

#include <metrica/io/mesh_data.hpp>

#include <string>

namespace metrica::io {

std::string format_su2(const MeshData& mesh);
void write_su2(const std::string& path, const MeshData& mesh);

}  // namespace metrica::io
