#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/msh.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/io/vtu.hpp>

#include <fmt/core.h>

#include <string_view>

namespace metrica::io {

FileFormat format_of(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return FileFormat::unknown;
  const std::string_view ext = std::string_view(path).substr(dot + 1);
  if (ext == "mesh") return FileFormat::mesh;
  if (ext == "meshb") return FileFormat::meshb;
  if (ext == "msh") return FileFormat::msh;
  if (ext == "sol") return FileFormat::sol;
  if (ext == "solb") return FileFormat::solb;
  if (ext == "vtu") return FileFormat::vtu;
  if (ext == "su2") return FileFormat::su2;
  return FileFormat::unknown;
}

const char* to_string(FileFormat f) {
  switch (f) {
    case FileFormat::mesh: return ".mesh";
    case FileFormat::meshb: return ".meshb";
    case FileFormat::msh: return ".msh";
    case FileFormat::sol: return ".sol";
    case FileFormat::solb: return ".solb";
    case FileFormat::vtu: return ".vtu";
    case FileFormat::su2: return ".su2";
    case FileFormat::unknown: return "unknown";
  }
  return "unknown";
}

MeshData read_mesh_file(const std::string& path) {
  const auto f = format_of(path);
  if (f == FileFormat::msh) return read_msh(path);
  if (f == FileFormat::vtu) return read_vtu(path);
  if (f == FileFormat::su2) return read_su2(path);
  if (f != FileFormat::mesh && f != FileFormat::meshb)
    throw IoError(fmt::format("{}: cannot read meshes of this format (use .mesh, .meshb, .msh, .vtu or .su2)", path));
  return read_meshb(path);
}

void write_mesh_file(const std::string& path, const MeshData& data, int version, const PartRunner& run,
                     FileFormat standard_output_format, Encoding msh_encoding) {
  switch (is_standard_output(path) ? standard_output_format : format_of(path)) {
    case FileFormat::mesh:
    case FileFormat::meshb: write_meshb(path, data, version, run); return;
    case FileFormat::msh: write_msh(path, data, version == 2 ? MshVersion::v22 : MshVersion::v41, msh_encoding); return;
    case FileFormat::vtu: write_vtu(path, data); return;
    case FileFormat::su2: write_su2(path, data); return;
    default: throw IoError(fmt::format("{}: unknown mesh output format (use .mesh, .meshb, .msh, .vtu or .su2)", path));
  }
}

}  // namespace metrica::io
