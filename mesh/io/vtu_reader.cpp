// Reading a .vtu (VTK XML UnstructuredGrid, one Piece): the DataArrays
// located by section (Points, Cells, PointData, CellData), their values read
// from the raw appended block or from ASCII text, then the tets and
// triangles picked out of the cells by type.
#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/vtu.hpp>
#include <metrica/log.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

namespace metrica::io {

namespace {

// The value of attribute `name` in the tag `tag` ("" when absent).
std::string attribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const bool starts = at > 0 && (tag[at - 1] == ' ' || tag[at - 1] == '\n' || tag[at - 1] == '\t');
    const std::size_t eq = at + name.size();
    if (!starts || eq + 1 >= tag.size() || tag[eq] != '=' || (tag[eq + 1] != '"' && tag[eq + 1] != '\'')) continue;
    const std::size_t end = tag.find(tag[eq + 1], eq + 2);
    if (end == std::string_view::npos) return {};
    return std::string(tag.substr(eq + 2, end - eq - 2));
  }
  return {};
}

struct Array {
  std::string section, name, type, format;
  int components = 1;
  std::uint64_t offset = 0;  // appended: where its count starts in the block
  std::string_view text;     // ascii: its values
};

std::size_t type_size(const std::string& type) {
  if (type == "Int8" || type == "UInt8") return 1;
  if (type == "Int16" || type == "UInt16") return 2;
  if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
  if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
  return 0;
}

template <class T>
T read_as(const char* p) {
  T x;
  std::memcpy(&x, p, sizeof x);
  return x;
}

template <class T>
double as_double(const char* p) {
  return static_cast<double>(read_as<T>(p));
}

double decode(const std::string& type, const char* p) {
  if (type == "Float64") return as_double<double>(p);
  if (type == "Float32") return as_double<float>(p);
  if (type == "Int64") return as_double<std::int64_t>(p);
  if (type == "UInt64") return as_double<std::uint64_t>(p);
  if (type == "Int32") return as_double<std::int32_t>(p);
  if (type == "UInt32") return as_double<std::uint32_t>(p);
  if (type == "Int16") return as_double<std::int16_t>(p);
  if (type == "UInt16") return as_double<std::uint16_t>(p);
  if (type == "Int8") return as_double<std::int8_t>(p);
  return as_double<std::uint8_t>(p);
}

class VtuFile {
 public:
  VtuFile(std::string bytes, std::string path) : path_(std::move(path)), bytes_(std::move(bytes)) {
    const std::string_view all(bytes_);
    const std::string root = tag_at(all.find("<VTKFile"));
    if (attribute(root, "type") != "UnstructuredGrid")
      fail("not a VTK UnstructuredGrid (type=\"{}\")", attribute(root, "type"));
    if (!attribute(root, "compressor").empty())
      fail(
          "compressed data ({}): write it without compression (meshio: compression=None) or read it with "
          "meshio and metrica.from_meshio",
          attribute(root, "compressor"));
    const std::string order = attribute(root, "byte_order");
    if (!order.empty() && order != "LittleEndian") fail("byte order {} (only LittleEndian is read)", order);
    header_bytes_ = attribute(root, "header_type") == "UInt64" ? 8 : 4;
    const std::size_t appended = all.find("<AppendedData");
    if (appended != std::string_view::npos) {
      const std::string tag = tag_at(appended);
      if (attribute(tag, "encoding") != "raw")
        fail("appended data encoded as {} (raw appended data and ASCII are read)", attribute(tag, "encoding"));
      block_ = all.find('_', appended + tag.size());
      if (block_ == std::string_view::npos) fail("the appended block has no '_' mark");
      ++block_;
    }
    const std::size_t piece = all.find("<Piece");
    if (piece == std::string_view::npos) fail("no Piece");
    if (all.find("<Piece", piece + 1) != std::string_view::npos) fail("several Pieces (one is read)");
    const std::string ptag = tag_at(piece);
    points_ = count_attribute(ptag, "NumberOfPoints");
    cells_ = count_attribute(ptag, "NumberOfCells");
    collect_arrays(all.substr(0, appended == std::string_view::npos ? all.size() : appended));
  }

  std::uint64_t points() const { return points_; }
  std::uint64_t cells() const { return cells_; }
  const std::vector<Array>& arrays() const { return arrays_; }

  const Array* find(std::string_view section, std::string_view name) const {
    for (const auto& a : arrays_)
      if (a.section == section && a.name == name) return &a;
    return nullptr;
  }
  const Array& need(std::string_view section, std::string_view name) const {
    if (const Array* a = find(section, name)) return *a;
    fail("no {} array '{}'", section, name);
  }

  // The values of `a` as doubles, `expected` of them.
  std::vector<double> values(const Array& a, std::uint64_t expected) const {
    const std::size_t size = type_size(a.type);
    if (size == 0) fail("array '{}' has type {}", a.name, a.type);
    std::vector<double> out;
    if (a.format == "appended") {
      if (block_ == 0) fail("array '{}' is appended but the file has no appended block", a.name);
      const std::uint64_t at = block_ + a.offset;
      if (at + header_bytes_ > bytes_.size()) fail("array '{}' starts past the end of the file", a.name);
      const std::uint64_t count =
          header_bytes_ == 8 ? read_as<std::uint64_t>(bytes_.data() + at) : read_as<std::uint32_t>(bytes_.data() + at);
      if (count != expected * size)
        fail("array '{}' holds {} bytes where {} values of {} bytes are expected", a.name, count, expected, size);
      if (at + header_bytes_ + count > bytes_.size()) fail("array '{}' runs past the end of the file", a.name);
      out.reserve(expected);
      for (std::uint64_t i = 0; i < expected; ++i)
        out.push_back(decode(a.type, bytes_.data() + at + header_bytes_ + i * size));
    } else if (a.format == "ascii") {
      const char* p = a.text.data();
      const char* end = p + a.text.size();
      out.reserve(std::min<std::uint64_t>(expected, a.text.size() / 2 + 1));  // a value takes 2 characters or more
      while (out.size() < expected) {
        while (p < end && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) ++p;
        double x = 0;
        const auto r = std::from_chars(p, end, x);
        if (r.ec != std::errc()) fail("array '{}' holds {} values where {} are expected", a.name, out.size(), expected);
        out.push_back(x);
        p = r.ptr;
      }
    } else {
      fail("array '{}' is in format \"{}\" (raw appended data and ASCII are read)", a.name, a.format);
    }
    for (double x : out)
      if (!std::isfinite(x)) fail("array '{}' holds a value that is not finite", a.name);
    return out;
  }

  template <class... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> f, Args&&... args) const {
    throw IoError(fmt::format("{}: {}", path_, fmt::format(f, std::forward<Args>(args)...)));
  }

  // x as an int when it is a whole number in int's range.
  int whole(double x, const char* what) const {
    if (!(std::abs(x) < 2147483647.0) || x != std::floor(x)) fail("{} is {} (a whole number is expected)", what, x);
    return int(x);
  }

 private:
  std::string tag_at(std::size_t at) const {
    if (at == std::string::npos) fail("no VTKFile element: not a VTK XML file");
    const std::size_t end = bytes_.find('>', at);
    if (end == std::string::npos) fail("an element is not closed");
    return bytes_.substr(at, end - at + 1);
  }

  std::uint64_t count_attribute(const std::string& tag, std::string_view name) const {
    const std::string text = attribute(tag, name);
    std::uint64_t n = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || n > (1ull << 40))
      fail("{} is \"{}\"", name, text);
    return n;
  }

  // Every DataArray before the appended block, with the section it is in.
  void collect_arrays(std::string_view xml) {
    std::string section;
    for (std::size_t at = xml.find('<'); at != std::string_view::npos; at = xml.find('<', at + 1)) {
      const std::string_view rest = xml.substr(at + 1);
      for (const char* s : {"Points", "Cells", "PointData", "CellData"}) {
        const std::string_view name(s);
        if (rest.size() > name.size() && rest.substr(0, name.size()) == name &&
            (rest[name.size()] == '>' || rest[name.size()] == ' '))
          section = name;
        if (rest.size() > name.size() && rest[0] == '/' && rest.substr(1, name.size()) == name) section.clear();
      }
      if (rest.substr(0, 9) != "DataArray") continue;
      const std::string tag = tag_at(at);
      Array a;
      a.section = section;
      a.name = attribute(tag, "Name");
      a.type = attribute(tag, "type");
      a.format = attribute(tag, "format");
      const std::string comps = attribute(tag, "NumberOfComponents");
      a.components = comps.empty() ? 1 : int(count_attribute(tag, "NumberOfComponents"));
      if (a.components < 1 || a.components > 9) fail("array '{}' has {} components", a.name, comps);
      if (a.format == "appended") a.offset = count_attribute(tag, "offset");
      if (a.format == "ascii" && tag[tag.size() - 2] != '/') {
        const std::size_t begin = at + tag.size(), end = xml.find("</DataArray", begin);
        if (end == std::string_view::npos) fail("array '{}' is not closed", a.name);
        a.text = xml.substr(begin, end - begin);
      }
      if (!section.empty()) arrays_.push_back(std::move(a));
    }
  }

  std::string path_;
  std::string bytes_;
  std::size_t header_bytes_ = 4;
  std::size_t block_ = 0;  // the appended block's first byte (0: none)
  std::uint64_t points_ = 0, cells_ = 0;
  std::vector<Array> arrays_;
};

constexpr int kVtkTriangle = 5, kVtkTetra = 10;

}  // namespace

VtuField vtu_tensor_field(std::string name, const std::vector<double>& m) {
  VtuField f{std::move(name), 6, std::vector<double>(m.size())};
  constexpr int kFromMeshb[6] = {0, 2, 5, 1, 4, 3};  // xx yy zz xy yz xz
  for (std::size_t v = 0; v + 5 < m.size(); v += 6)
    for (int k = 0; k < 6; ++k) f.values[v + k] = m[v + kFromMeshb[k]];
  return f;
}

MeshData read_vtu(const std::string& path, std::vector<VtuField>* point_fields) {
  return parse_vtu(read_file_bytes(path), path, point_fields);
}

MeshData parse_vtu(std::string bytes, const std::string& path, std::vector<VtuField>* point_fields) {
  const VtuFile file(std::move(bytes), path);
  const std::uint64_t nv = file.points(), nc = file.cells();
  const Array* points = nullptr;
  for (const auto& a : file.arrays())
    if (a.section == "Points") points = &a;
  if (!points) file.fail("no Points array");
  if (points->components != 3) file.fail("the points have {} components (3 are read)", points->components);
  const std::vector<double> xyz = file.values(*points, 3 * nv);
  const std::vector<double> offsets = file.values(file.need("Cells", "offsets"), nc);
  const std::vector<double> types = file.values(file.need("Cells", "types"), nc);
  const double corners = nc == 0 ? 0.0 : offsets.back();
  if (!(corners >= 0 && corners < double(std::numeric_limits<std::int64_t>::max())))
    file.fail("the last cell offset is {}", corners);
  const std::vector<double> connectivity = file.values(file.need("Cells", "connectivity"), std::uint64_t(corners));
  const Array* ref = file.find("CellData", "ref");
  for (const char* name : {"medit:ref", "gmsh:physical"})
    if (!ref) ref = file.find("CellData", name);
  const std::vector<double> ids = ref ? file.values(*ref, nc) : std::vector<double>(nc, 0.0);

  MeshData data;
  data.vertices.resize(nv);
  for (std::uint64_t v = 0; v < nv; ++v) data.vertices[v] = Point(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
  std::uint64_t left_out = 0;
  double start = 0;
  for (std::uint64_t c = 0; c < nc; start = offsets[c], ++c) {
    const double size = offsets[c] - start;
    const int type = file.whole(types[c], "a cell type");
    const int need = type == kVtkTetra ? 4 : type == kVtkTriangle ? 3 : -1;
    if (need < 0) {
      ++left_out;
      continue;
    }
    if (size != need || start < 0 || offsets[c] > corners)
      file.fail("cell {} of type {} has offsets {} to {} (of {})", numbered(c), type, start, offsets[c], corners);
    std::array<VertexId, 4> v{};
    for (int i = 0; i < need; ++i) {
      const double x = connectivity[std::size_t(start) + std::size_t(i)];
      if (!(x >= 0 && x < double(nv)) || x != std::floor(x))
        file.fail("cell {} names vertex {} (the file has {})", numbered(c), x, nv);
      v[std::size_t(i)] = VertexId(x);
    }
    const int id = file.whole(ids[c], "a cell's id");
    if (type == kVtkTetra) {
      data.tets.push_back({v[0], v[1], v[2], v[3]});
      data.tet_refs.push_back(id);
    } else {
      data.triangles.push_back({v[0], v[1], v[2]});
      data.triangle_refs.push_back(id);
    }
  }
  if (left_out > 0) log::warn("{}: {} cells neither tets nor triangles left out", path, left_out);
  if (data.tets.empty()) file.fail("no tetrahedra");
  if (point_fields)
    for (const auto& a : file.arrays())
      if (a.section == "PointData")
        point_fields->push_back({a.name, a.components, file.values(a, nv * std::uint64_t(a.components))});
  return data;
}

}  // namespace metrica::io
