#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/msh.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>

namespace metrica::io {
namespace {

struct Box {
  Point lo = Point::Constant(std::numeric_limits<double>::max());
  Point hi = Point::Constant(-std::numeric_limits<double>::max());
  void add(const Point& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// The elements of one entity: its tag (and physical group), the indices
// of its elements in the mesh's list, their bounding box.
struct Entity {
  int tag = 0;
  int physical = 0;  // 0: none (a ref <= 0)
  std::vector<std::size_t> elements;
  Box box;
};

template <class Elements, class Refs>
std::vector<Entity> entities_by_ref(const MeshData& m, const Elements& elements, const Refs& refs) {
  std::map<int, Entity> by_ref;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const int ref = i < refs.size() ? refs[i] : 0;
    Entity& e = by_ref[ref];
    e.elements.push_back(i);
    for (VertexId v : elements[i]) e.box.add(m.vertices[v]);
  }
  std::vector<Entity> out;
  int next = 1;
  for (auto& [ref, e] : by_ref) {
    e.tag = next++;
    e.physical = ref > 0 ? ref : 0;
    out.push_back(std::move(e));
  }
  return out;
}

void append_box(std::string& s, const Box& b) {
  fmt::format_to(std::back_inserter(s), "{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}", b.lo.x(), b.lo.y(), b.lo.z(),
                 b.hi.x(), b.hi.y(), b.hi.z());
}

std::string format_41(const MeshData& m) {
  const auto surfaces = entities_by_ref(m, m.triangles, m.triangle_refs);
  const auto volumes = entities_by_ref(m, m.tets, m.tet_refs);
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n";
  auto out = std::back_inserter(s);
  fmt::format_to(out, "0 0 {} {}\n", surfaces.size(), volumes.size());
  for (const auto* list : {&surfaces, &volumes})
    for (const Entity& e : *list) {
      fmt::format_to(out, "{} ", e.tag);
      append_box(s, e.box);
      if (e.physical > 0)
        fmt::format_to(out, " 1 {} 0\n", e.physical);
      else
        s += " 0 0\n";
    }
  s += "$EndEntities\n$Nodes\n";
  // One block of every node, in the first volume (gmsh sorts nodes to
  // entities itself when it reads).
  const std::size_t n = m.vertices.size();
  const int home = volumes.empty() ? 1 : volumes.front().tag;
  fmt::format_to(out, "1 {} 1 {}\n3 {} 0 {}\n", n, n, home, n);
  for (std::size_t v = 1; v <= n; ++v) fmt::format_to(out, "{}\n", v);
  for (const Point& p : m.vertices) fmt::format_to(out, "{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  s += "$EndNodes\n$Elements\n";
  const std::size_t count = m.triangles.size() + m.tets.size();
  fmt::format_to(out, "{} {} 1 {}\n", surfaces.size() + volumes.size(), count, count);
  std::size_t tag = 1;
  for (const Entity& e : surfaces) {
    fmt::format_to(out, "2 {} 2 {}\n", e.tag, e.elements.size());
    for (std::size_t i : e.elements) {
      const auto& t = m.triangles[i];
      fmt::format_to(out, "{} {} {} {}\n", tag++, t[0] + 1, t[1] + 1, t[2] + 1);
    }
  }
  for (const Entity& e : volumes) {
    fmt::format_to(out, "3 {} 4 {}\n", e.tag, e.elements.size());
    for (std::size_t i : e.elements) {
      const auto& t = m.tets[i];
      fmt::format_to(out, "{} {} {} {} {}\n", tag++, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
  }
  s += "$EndElements\n";
  return s;
}

std::string format_22(const MeshData& m) {
  std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n";
  auto out = std::back_inserter(s);
  fmt::format_to(out, "{}\n", m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    fmt::format_to(out, "{} {:.17g} {:.17g} {:.17g}\n", v + 1, m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z());
  s += "$EndNodes\n$Elements\n";
  fmt::format_to(out, "{}\n", m.triangles.size() + m.tets.size());
  std::size_t tag = 1;
  // Tags: the physical group, then the elementary entity (the same number).
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const int ref = i < m.triangle_refs.size() ? m.triangle_refs[i] : 0;
    const auto& t = m.triangles[i];
    fmt::format_to(out, "{} 2 2 {} {} {} {} {}\n", tag++, ref, std::max(ref, 1), t[0] + 1, t[1] + 1, t[2] + 1);
  }
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const int ref = i < m.tet_refs.size() ? m.tet_refs[i] : 0;
    const auto& t = m.tets[i];
    fmt::format_to(out, "{} 4 2 {} {} {} {} {} {}\n", tag++, ref, std::max(ref, 1), t[0] + 1, t[1] + 1, t[2] + 1,
                   t[3] + 1);
  }
  s += "$EndElements\n";
  return s;
}

}  // namespace

std::string format_msh(const MeshData& mesh, MshVersion version) {
  return version == MshVersion::v22 ? format_22(mesh) : format_41(mesh);
}

void write_msh(const std::string& path, const MeshData& mesh, MshVersion version) {
  for (const Point& p : mesh.vertices)
    if (!p.allFinite()) throw IoError(fmt::format("{}: a vertex has a coordinate that is not finite", path));
  write_file_atomically(path, format_msh(mesh, version));
}

}  // namespace metrica::io
