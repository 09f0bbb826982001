#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/vtu.hpp>
#include <metrica/numbering.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace metrica::io {

VtuLayout::VtuLayout(std::uint64_t vertices, std::uint64_t tets, const std::vector<FieldShape>& point_fields,
                     const std::vector<FieldShape>& cell_fields, std::uint64_t triangles)
    : point_fields_(point_fields.size()) {
  const std::uint64_t cells = tets + triangles;
  std::uint64_t offset = 0;
  auto add = [&](const char* type, const std::string& name, int components, std::uint64_t bytes) {
    arrays_.push_back({type, name, components, bytes, offset});
    offset += 8 + bytes;
  };
  add("Float64", "Points", 3, 24 * vertices);
  add("Int64", "connectivity", 1, 32 * tets + 24 * triangles);
  add("Int64", "offsets", 1, 8 * cells);
  add("UInt8", "types", 1, cells);
  for (const auto& f : point_fields) add("Float64", f.name, f.components, 8 * vertices * std::uint64_t(f.components));
  add("Int32", "ref", 1, 4 * cells);
  for (const auto& f : cell_fields) add("Float64", f.name, f.components, 8 * cells * std::uint64_t(f.components));

  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  auto array = [&](std::size_t k) {
    const Array& a = arrays_[k];
    fmt::format_to(it,
                   "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                   "offset=\"{}\"/>\n",
                   a.type, a.name, a.components, a.offset);
  };
  fmt::format_to(it,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
                 "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <Points>\n",
                 vertices, cells);
  array(kPoints);
  fmt::format_to(it, "      </Points>\n      <Cells>\n");
  for (std::size_t k : {kConnectivity, kOffsets, kTypes}) array(k);
  fmt::format_to(it, "      </Cells>\n      <PointData>\n");
  for (std::size_t k = kFirstPointField; k < refs(); ++k) array(k);
  fmt::format_to(it, "      </PointData>\n      <CellData>\n");
  for (std::size_t k = refs(); k < arrays_.size(); ++k) array(k);
  fmt::format_to(it,
                 "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"
                 "  <AppendedData encoding=\"raw\">\n   _");
  head_ = fmt::to_string(out);
}

std::uint64_t VtuLayout::tail_at() const { return values_at(arrays_.size() - 1) + arrays_.back().bytes; }

namespace {

void check_field(const VtuField& f, std::size_t entities, const char* kind) {
  if (f.components < 1 || f.values.size() != entities * std::size_t(f.components))
    throw InputError(fmt::format("vtu field '{}': {} values for {} {} x {} components", f.name, f.values.size(),
                                 entities, kind, f.components));
}

std::vector<VtuLayout::FieldShape> shapes(const std::vector<VtuField>& fields) {
  std::vector<VtuLayout::FieldShape> out;
  for (const auto& f : fields) out.push_back({f.name, f.components});
  return out;
}

}  // namespace

std::string format_vtu(const MeshData& m, const std::vector<VtuField>& point_fields,
                       const std::vector<VtuField>& cell_fields) {
  const std::size_t nv = m.vertices.size(), nt = m.tets.size(), nf = m.triangles.size();
  for (const auto& f : point_fields) check_field(f, nv, "vertices");
  for (const auto& f : cell_fields) check_field(f, nt, "tets");
  const VtuLayout layout(nv, nt, shapes(point_fields), shapes(cell_fields), nf);
  std::string out(layout.tail_at(), '\0');
  std::memcpy(out.data(), layout.head().data(), layout.head().size());
  // Each array: its byte count, then its values at values_at(k).
  for (std::size_t k = 0; k < layout.arrays().size(); ++k) out.replace(layout.count_at(k), 8, layout.count_bytes(k));
  auto put = [&](std::size_t k, std::size_t i, const auto& value) {
    std::memcpy(out.data() + layout.values_at(k) + i * sizeof(value), &value, sizeof(value));
  };
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) put(VtuLayout::kPoints, 3 * v + c, double(m.vertices[v][c]));
  for (std::size_t t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) put(VtuLayout::kConnectivity, 4 * t + i, std::int64_t(m.tets[t][i]));
    put(VtuLayout::kOffsets, t, std::int64_t(4 * (t + 1)));
    put(VtuLayout::kTypes, t, std::uint8_t(10));  // VTK_TETRA
    put(layout.refs(), t, std::int32_t(t < m.tet_refs.size() ? m.tet_refs[t] : 0));
  }
  // The surface triangles after the tets, their surface ids as "ref".
  for (std::size_t f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) put(VtuLayout::kConnectivity, 4 * nt + 3 * f + i, std::int64_t(m.triangles[f][i]));
    put(VtuLayout::kOffsets, nt + f, std::int64_t(4 * nt + 3 * (f + 1)));
    put(VtuLayout::kTypes, nt + f, std::uint8_t(5));  // VTK_TRIANGLE
    put(layout.refs(), nt + f, std::int32_t(f < m.triangle_refs.size() ? m.triangle_refs[f] : 0));
  }
  for (std::size_t f = 0; f < point_fields.size(); ++f)
    for (std::size_t i = 0; i < point_fields[f].values.size(); ++i)
      put(VtuLayout::kFirstPointField + f, i, point_fields[f].values[i]);
  // Cell fields are the tets'; the triangles' entries are NaN (undefined).
  for (std::size_t f = 0; f < cell_fields.size(); ++f) {
    const auto& values = cell_fields[f].values;
    const auto components = static_cast<std::size_t>(cell_fields[f].components);
    for (std::size_t i = 0; i < values.size(); ++i) put(layout.refs() + 1 + f, i, values[i]);
    for (std::size_t i = values.size(); i < components * (nt + nf); ++i)
      put(layout.refs() + 1 + f, i, std::numeric_limits<double>::quiet_NaN());
  }
  out += VtuLayout::tail();
  return out;
}

void write_vtu(const std::string& path, const MeshData& mesh, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields) {
  check_finite(mesh, path);
  for (const auto& f : point_fields)
    for (std::size_t i = 0; i < f.values.size(); ++i)
      if (!std::isfinite(f.values[i]))
        throw IoError(fmt::format("{}: field {} is not finite at vertex {}; nothing written", path, f.name,
                                  numbered(i / std::size_t(std::max(1, f.components)))));
  write_file_atomically(path, format_vtu(mesh, point_fields, cell_fields));
}

}  // namespace metrica::io
