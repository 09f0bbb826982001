#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/log.hpp>
#include <metrica/numbering.hpp>

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

namespace metrica::io {

std::string format_su2(const MeshData& m) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "NDIME= 3\nNELEM= {}\n", m.tets.size());
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const auto& v = m.tets[t];
    fmt::format_to(it, "10 {} {} {} {} {}\n", v[0], v[1], v[2], v[3], t);  // 10: VTK_TETRA, 0-based
  }
  fmt::format_to(it, "NPOIN= {}\n", m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    fmt::format_to(it, "{} {} {} {}\n", m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z(), v);
  std::map<int, std::vector<std::size_t>> markers;
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    markers[i < m.triangle_refs.size() ? m.triangle_refs[i] : 0].push_back(i);
  fmt::format_to(it, "NMARK= {}\n", markers.size());
  for (const auto& [ref, tris] : markers) {
    fmt::format_to(it, "MARKER_TAG= {}\nMARKER_ELEMS= {}\n", ref, tris.size());
    for (auto i : tris) {
      const auto& t = m.triangles[i];
      fmt::format_to(it, "5 {} {} {}\n", t[0], t[1], t[2]);  // 5: VTK_TRIANGLE
    }
  }
  return fmt::to_string(out);
}

void write_su2(const std::string& path, const MeshData& mesh) {
  check_finite(mesh, path);
  write_file_atomically(path, format_su2(mesh));
}

namespace {

// The lines of an .su2 file, comments ('%' to the end of a line) and blank
// lines skipped; numbers read off a line one by one.
class Su2Lines {
 public:
  Su2Lines(std::string text, std::string path) : path_(std::move(path)), text_(std::move(text)) {}

  // The next line that holds something, or false at the end.
  bool next() {
    while (at_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', at_), text_.size());
      line_ = std::string_view(text_).substr(at_, end - at_);
      at_ = end + 1;
      ++number_;
      line_ = line_.substr(0, line_.find('%'));
      while (!line_.empty() && std::isspace(static_cast<unsigned char>(line_.back()))) line_.remove_suffix(1);
      while (!line_.empty() && std::isspace(static_cast<unsigned char>(line_.front()))) line_.remove_prefix(1);
      if (!line_.empty()) return true;
    }
    return false;
  }
  void need_line(const char* what) {
    if (!next()) fail("the file ends before {}", what);
  }
  // "KEY= value" on the current line: the value, or "" when the key differs.
  std::string_view value_of(std::string_view key) const {
    if (line_.substr(0, key.size()) != key || line_.size() <= key.size() || line_[key.size()] != '=') return {};
    std::string_view v = line_.substr(key.size() + 1);
    while (!v.empty() && std::isspace(static_cast<unsigned char>(v.front()))) v.remove_prefix(1);
    return v;
  }
  template <class T>
  T number(std::string_view& rest, const char* what) const {
    while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.front()))) rest.remove_prefix(1);
    T x{};
    const auto r = std::from_chars(rest.data(), rest.data() + rest.size(), x);
    if (r.ec != std::errc()) fail("expected {} in \"{}\"", what, line_);
    rest.remove_prefix(static_cast<std::size_t>(r.ptr - rest.data()));
    return x;
  }
  std::string_view line() const { return line_; }

  template <class... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> f, Args&&... args) const {
    throw IoError(fmt::format("{}:{}: {}", path_, number_, fmt::format(f, std::forward<Args>(args)...)));
  }

 private:
  std::string path_, text_;
  std::size_t at_ = 0, number_ = 0;
  std::string_view line_;
};

constexpr std::size_t kMaxSu2Count = std::size_t(1) << 34;

}  // namespace

MeshData read_su2(const std::string& path) { return parse_su2(read_file_bytes(path), path); }

MeshData parse_su2(std::string text, const std::string& path) {
  Su2Lines in(std::move(text), path);
  MeshData d;
  std::size_t nv = 0;
  bool have_points = false;
  std::vector<std::array<std::size_t, 4>> tets;
  std::vector<std::array<std::size_t, 3>> triangles;
  int next_marker_id = 1;
  std::map<std::string, int, std::less<>> named;  // marker names that are not numbers
  while (in.next()) {
    if (auto dim = in.value_of("NDIME"); !dim.empty()) {
      if (in.number<int>(dim, "the dimension") != 3) in.fail("a {}-dimensional mesh (3 is read)", in.line());
    } else if (auto elems = in.value_of("NELEM"); !elems.empty()) {
      const auto n = in.number<std::size_t>(elems, "the element count");
      if (n > kMaxSu2Count) in.fail("NELEM= {} is not a count", n);
      for (std::size_t e = 0; e < n; ++e) {
        in.need_line("the last element");
        std::string_view rest = in.line();
        const int type = in.number<int>(rest, "an element type");
        if (type != 10) in.fail("element {} has VTK type {} (only tetrahedra, 10, are read)", numbered(e), type);
        std::array<std::size_t, 4> t{};
        for (auto& x : t) x = in.number<std::size_t>(rest, "a vertex index");
        tets.push_back(t);
      }
    } else if (auto points = in.value_of("NPOIN"); !points.empty()) {
      nv = in.number<std::size_t>(points, "the point count");
      if (nv > kMaxSu2Count) in.fail("NPOIN= {} is not a count", nv);
      d.vertices.clear();
      for (std::size_t p = 0; p < nv; ++p) {
        in.need_line("the last point");
        std::string_view rest = in.line();
        Point x;
        for (int c = 0; c < 3; ++c) x[c] = in.number<double>(rest, "a coordinate");
        if (!x.allFinite()) in.fail("point {} has a coordinate that is not finite", numbered(p));
        d.vertices.push_back(x);
      }
      have_points = true;
    } else if (auto marks = in.value_of("NMARK"); !marks.empty()) {
      static_cast<void>(in.number<std::size_t>(marks, "the marker count"));
    } else if (auto v = in.value_of("MARKER_TAG"); !v.empty()) {
      // A number is the surface id; a name gets the next free id.
      int id = 0;
      const auto r = std::from_chars(v.data(), v.data() + v.size(), id);
      if (r.ec != std::errc() || r.ptr != v.data() + v.size() || id <= 0) {
        auto [it, added] = named.try_emplace(std::string(v), 0);
        if (added) it->second = 1000 + next_marker_id++;
        id = it->second;
      }
      in.need_line("MARKER_ELEMS");
      auto count = in.value_of("MARKER_ELEMS");
      if (count.empty()) in.fail("expected MARKER_ELEMS= after MARKER_TAG=");
      const auto n = in.number<std::size_t>(count, "the marker's element count");
      if (n > kMaxSu2Count) in.fail("MARKER_ELEMS= {} is not a count", n);
      for (std::size_t e = 0; e < n; ++e) {
        in.need_line("the marker's last element");
        std::string_view rest = in.line();
        const int type = in.number<int>(rest, "an element type");
        if (type != 5) in.fail("a marker element of VTK type {} (triangles, 5, are read)", type);
        std::array<std::size_t, 3> t{};
        for (auto& x : t) x = in.number<std::size_t>(rest, "a vertex index");
        triangles.push_back(t);
        d.triangle_refs.push_back(id);
      }
    }
  }
  if (!have_points) throw IoError(fmt::format("{}: no NPOIN= section", path));
  if (tets.empty()) throw IoError(fmt::format("{}: no tetrahedra (NELEM=)", path));
  const auto vertex = [&](std::size_t x, const char* what, std::size_t i) {
    if (x >= nv)
      throw IoError(fmt::format("{}: {} {} names point {} (the file has {})", path, what, numbered(i), x, nv));
    return static_cast<VertexId>(x);
  };
  for (std::size_t i = 0; i < tets.size(); ++i)
    d.tets.push_back({vertex(tets[i][0], "element", i), vertex(tets[i][1], "element", i),
                      vertex(tets[i][2], "element", i), vertex(tets[i][3], "element", i)});
  d.tet_refs.assign(d.tets.size(), 0);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    d.triangles.push_back({vertex(triangles[i][0], "marker element", i), vertex(triangles[i][1], "marker element", i),
                           vertex(triangles[i][2], "marker element", i)});
  for (const auto& [name, id] : named) log::info("{}: marker {} is surface id {}", path, name, id);
  return d;
}

}  // namespace metrica::io
