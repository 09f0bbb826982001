#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/vtu.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace metrica::io {

std::string base64(const void* data, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t w = (std::uint32_t(p[i]) << 16) | (std::uint32_t(p[i + 1]) << 8) | p[i + 2];
    out += kAlphabet[w >> 18];
    out += kAlphabet[(w >> 12) & 63];
    out += kAlphabet[(w >> 6) & 63];
    out += kAlphabet[w & 63];
  }
  if (i < size) {
    std::uint32_t w = std::uint32_t(p[i]) << 16;
    if (i + 1 < size) w |= std::uint32_t(p[i + 1]) << 8;
    out += kAlphabet[w >> 18];
    out += kAlphabet[(w >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(w >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

namespace {

// One DataArray: a UInt64 byte count then the values, base64-encoded.
template <class T>
void data_array(fmt::memory_buffer& out, const char* type, const std::string& name, int components,
                const std::vector<T>& values) {
  std::string bytes(8 + values.size() * sizeof(T), '\0');
  const std::uint64_t n = values.size() * sizeof(T);
  std::memcpy(bytes.data(), &n, 8);
  if (!values.empty()) std::memcpy(bytes.data() + 8, values.data(), n);
  fmt::format_to(std::back_inserter(out),
                 "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n"
                 "          {}\n        </DataArray>\n",
                 type, name, components, base64(bytes.data(), bytes.size()));
}

void check_field(const VtuField& f, std::size_t entities, const char* kind) {
  if (f.components < 1 || f.values.size() != entities * std::size_t(f.components))
    throw InputError(fmt::format("vtu field '{}': {} values for {} {} x {} components", f.name, f.values.size(),
                                 entities, kind, f.components));
}

}  // namespace

std::string format_vtu(const MeshData& m, const std::vector<VtuField>& point_fields,
                       const std::vector<VtuField>& cell_fields) {
  const std::size_t nv = m.vertices.size(), nt = m.tets.size();
  for (const auto& f : point_fields) check_field(f, nv, "vertices");
  for (const auto& f : cell_fields) check_field(f, nt, "tets");

  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
                 "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <Points>\n",
                 nv, nt);
  std::vector<double> xyz(3 * nv);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) xyz[3 * v + c] = m.vertices[v][c];
  data_array(out, "Float64", "Points", 3, xyz);
  fmt::format_to(it, "      </Points>\n      <Cells>\n");
  std::vector<std::int64_t> connectivity(4 * nt), offsets(nt);
  std::vector<std::uint8_t> types(nt, 10);  // VTK_TETRA
  for (std::size_t t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) connectivity[4 * t + i] = m.tets[t][i];
    offsets[t] = static_cast<std::int64_t>(4 * (t + 1));
  }
  data_array(out, "Int64", "connectivity", 1, connectivity);
  data_array(out, "Int64", "offsets", 1, offsets);
  data_array(out, "UInt8", "types", 1, types);
  fmt::format_to(it, "      </Cells>\n      <PointData>\n");
  for (const auto& f : point_fields) data_array(out, "Float64", f.name, f.components, f.values);
  fmt::format_to(it, "      </PointData>\n      <CellData>\n");
  std::vector<std::int32_t> refs(nt, 0);
  for (std::size_t t = 0; t < nt && t < m.tet_refs.size(); ++t) refs[t] = m.tet_refs[t];
  data_array(out, "Int32", "ref", 1, refs);
  for (const auto& f : cell_fields) data_array(out, "Float64", f.name, f.components, f.values);
  fmt::format_to(it, "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  return fmt::to_string(out);
}

void write_vtu(const std::string& path, const MeshData& mesh, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields) {
  check_finite(mesh, path);
  for (const auto& f : point_fields)
    for (std::size_t i = 0; i < f.values.size(); ++i)
      if (!std::isfinite(f.values[i]))
        throw IoError(fmt::format("{}: field {} is not finite at vertex {}; nothing written", path, f.name,
                                  i / std::size_t(std::max(1, f.components)) + 1));
  write_file_atomically(path, format_vtu(mesh, point_fields, cell_fields));
}

}  // namespace metrica::io
