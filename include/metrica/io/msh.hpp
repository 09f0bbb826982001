// gmsh's .msh files, versions 2.2 and 4.1, ASCII and binary (both byte
// orders of a binary file are read).
//
// Read: the nodes; tetrahedra with the physical group of their volume as
// tet ref (region), triangles with their surface's as surface id, lines as
// feature edges with their curve's, points as corners. A version 4.1
// file's elements take the first physical tag of their entity ($Entities),
// or the entity's own tag when it has none; a 2.2 file's the first tag of
// the element (physical), or the second (elementary) when that is 0.
// Second-order tets and triangles keep their corner nodes; other elements
// (quadrangles, prisms, pyramids, hexahedra, higher orders) are dropped,
// and a warning says how many of each. Every error is an IoError naming
// the file and the section.
//
// Written: version 4.1 (or 2.2), ASCII or binary: the nodes, one surface entity per
// surface id and one volume entity per tet ref, each with a physical group
// of that number (gmsh reads them back as physical groups).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/io/meshb.hpp>

#include <string>
#include <string_view>

namespace metrica::io {

enum class MshVersion { v22, v41 };

MeshData read_msh(const std::string& path);
MeshData parse_msh(std::string_view bytes, const std::string& name);

std::string format_msh(const MeshData& mesh, MshVersion version = MshVersion::v41, Encoding encoding = Encoding::ascii);
// Through a temporary renamed on success.
void write_msh(const std::string& path, const MeshData& mesh, MshVersion version = MshVersion::v41,
               Encoding encoding = Encoding::ascii);

}  // namespace metrica::io
