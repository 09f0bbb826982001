// VTK unstructured grid (.vtu) for ParaView: tets with per-vertex and
// per-tet fields, data base64-encoded inline (format="binary").
#pragma once

#include <metrica/io/mesh_data.hpp>

#include <string>
#include <vector>

namespace metrica::io {

struct VtuField {
  std::string name;
  int components = 1;          // 1 scalar, 3 vector, 6 or 9 tensor
  std::vector<double> values;  // size = entities * components
};

// Writes the tets of `mesh` (with their reference as the cell field "ref"),
// plus the given point fields (one entry per vertex) and cell fields (one
// entry per tet). Written through a temporary file and renamed.
void write_vtu(const std::string& path, const MeshData& mesh, const std::vector<VtuField>& point_fields = {},
               const std::vector<VtuField>& cell_fields = {});

std::string format_vtu(const MeshData& mesh, const std::vector<VtuField>& point_fields,
                       const std::vector<VtuField>& cell_fields);

// Base64 of raw bytes (RFC 4648, with padding), as VTK's binary mode wants.
std::string base64(const void* data, std::size_t size);

}  // namespace metrica::io
