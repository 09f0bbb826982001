#include <metrica/io/atomic_file.hpp>
#include <metrica/io/su2.hpp>

#include <fmt/format.h>

#include <map>

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

}  // namespace metrica::io
