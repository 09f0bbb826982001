// File formats by extension, and reading / writing a mesh whatever its
// format (the `metrica` command's -i / -o follow the extension).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/part_runner.hpp>

#include <string>

namespace metrica::io {

enum class FileFormat { mesh, meshb, msh, sol, solb, vtu, su2, unknown };

FileFormat format_of(const std::string& path);
const char* to_string(FileFormat f);

// .mesh, .meshb, gmsh's .msh, VTK's .vtu or SU2's .su2; IoError for other
// formats.
MeshData read_mesh_file(const std::string& path);

// .mesh, .meshb (libMeshb `version`, 0 = keep data.version), .msh (4.1;
// `version` 2: 2.2; ASCII or `msh_encoding`), .vtu, .su2;
// a .mesh's rows formatted on run's parts.
// "-" writes standard_output_format (ASCII .mesh unless said) to standard output.
void write_mesh_file(const std::string& path, const MeshData& data, int version = 0, const PartRunner& run = {},
                     FileFormat standard_output_format = FileFormat::mesh, Encoding msh_encoding = Encoding::ascii);

}  // namespace metrica::io
