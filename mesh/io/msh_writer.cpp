#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/msh.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
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
  bool grouped = false;  // in a physical group, numbered `physical`
  int physical = 0;
  std::vector<std::size_t> elements;
  Box box;
};

// Every entity is in the physical group of its ref as soon as one ref of
// the mesh is not 0 (id 0 included: a file whose volumes are partly in
// groups is one that readers refuse, meshio and ours among them); none is
// when every ref is 0.
bool any_ref(const MeshData& m) {
  const auto nonzero = [](int r) { return r != 0; };
  return std::any_of(m.triangle_refs.begin(), m.triangle_refs.end(), nonzero) ||
         std::any_of(m.tet_refs.begin(), m.tet_refs.end(), nonzero);
}

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
  const bool grouped = any_ref(m);
  for (auto& [ref, e] : by_ref) {
    e.tag = next++;
    e.grouped = grouped;
    e.physical = ref;
    out.push_back(std::move(e));
  }
  return out;
}

void append_box(std::string& s, const Box& b) {
  fmt::format_to(std::back_inserter(s), "{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}", b.lo.x(), b.lo.y(), b.lo.z(),
                 b.hi.x(), b.hi.y(), b.hi.z());
}

// Binary records in the machine's byte order (gmsh writes the number 1
// after the header so that readers can tell).
struct Bytes {
  std::string& s;
  template <class T>
  void put(T x) {
    char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));
    s.append(b, sizeof(T));
  }
  void size(std::size_t n) { put<std::uint64_t>(n); }
  void tag(int t) { put<std::int32_t>(t); }
  void point(const Point& p) {
    put(p.x());
    put(p.y());
    put(p.z());
  }
};

void binary_header(std::string& s, const char* version) {
  s = fmt::format("$MeshFormat\n{} 1 8\n", version);
  Bytes{s}.put<std::int32_t>(1);
  s += "\n$EndMeshFormat\n";
}

// Version 4.1 binary: sizes as 64-bit, tags and types as 32-bit integers,
// coordinates and boxes as doubles.
std::string format_41_binary(const MeshData& m) {
  const auto surfaces = entities_by_ref(m, m.triangles, m.triangle_refs);
  const auto volumes = entities_by_ref(m, m.tets, m.tet_refs);
  std::string s;
  binary_header(s, "4.1");
  Bytes b{s};
  s += "$Entities\n";
  for (std::size_t n : {std::size_t{0}, std::size_t{0}, surfaces.size(), volumes.size()}) b.size(n);
  for (const auto* list : {&surfaces, &volumes})
    for (const Entity& e : *list) {
      b.tag(e.tag);
      b.point(e.box.lo);
      b.point(e.box.hi);
      b.size(e.grouped ? 1 : 0);
      if (e.grouped) b.tag(e.physical);
      b.size(0);  // no bounding entities
    }
  s += "\n$EndEntities\n$Nodes\n";
  const std::size_t n = m.vertices.size();
  for (std::size_t x : {std::size_t{1}, n, std::size_t{1}, n}) b.size(x);
  b.tag(3);
  b.tag(volumes.empty() ? 1 : volumes.front().tag);
  b.tag(0);
  b.size(n);
  for (std::size_t v = 1; v <= n; ++v) b.size(v);
  for (const Point& p : m.vertices) b.point(p);
  s += "\n$EndNodes\n$Elements\n";
  const std::size_t count = m.triangles.size() + m.tets.size();
  for (std::size_t x : {surfaces.size() + volumes.size(), count, std::size_t{1}, count}) b.size(x);
  std::size_t tag = 1;
  auto block = [&](int dim, const Entity& e, int type, const auto& elements) {
    b.tag(dim);
    b.tag(e.tag);
    b.tag(type);
    b.size(e.elements.size());
    for (std::size_t i : e.elements) {
      b.size(tag++);
      for (VertexId v : elements[i]) b.size(std::size_t{v} + 1);
    }
  };
  for (const Entity& e : surfaces) block(2, e, 2, m.triangles);
  for (const Entity& e : volumes) block(3, e, 4, m.tets);
  s += "\n$EndElements\n";
  return s;
}

// Version 2.2 binary: each element type in one block (type, count, two
// tags), then per element its number, physical and elementary tags and
// nodes, all 32-bit.
std::string format_22_binary(const MeshData& m) {
  std::string s;
  binary_header(s, "2.2");
  Bytes b{s};
  s += fmt::format("$Nodes\n{}\n", m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    b.tag(static_cast<int>(v + 1));
    b.point(m.vertices[v]);
  }
  s += fmt::format("\n$EndNodes\n$Elements\n{}\n", m.triangles.size() + m.tets.size());
  int tag = 1;
  auto block = [&](int type, const auto& elements, const std::vector<int>& refs) {
    if (elements.empty()) return;
    b.tag(type);
    b.tag(static_cast<int>(elements.size()));
    b.tag(2);
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const int ref = i < refs.size() ? refs[i] : 0;
      b.tag(tag++);
      b.tag(ref);
      b.tag(std::max(ref, 1));
      for (VertexId v : elements[i]) b.tag(static_cast<int>(v + 1));
    }
  };
  block(2, m.triangles, m.triangle_refs);
  block(4, m.tets, m.tet_refs);
  s += "\n$EndElements\n";
  return s;
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
      if (e.grouped)
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

std::string format_msh(const MeshData& mesh, MshVersion version, Encoding encoding) {
  if (encoding == Encoding::binary) {
    // 32-bit indices in 2.2's binary records.
    if (version == MshVersion::v22 && std::max(mesh.vertices.size(), mesh.triangles.size() + mesh.tets.size()) >
                                          std::size_t(std::numeric_limits<std::int32_t>::max()))
      throw IoError("the mesh is too large for a binary .msh 2.2 file (32-bit numbers): write version 4.1");
    return version == MshVersion::v22 ? format_22_binary(mesh) : format_41_binary(mesh);
  }
  return version == MshVersion::v22 ? format_22(mesh) : format_41(mesh);
}

void write_msh(const std::string& path, const MeshData& mesh, MshVersion version, Encoding encoding) {
  for (const Point& p : mesh.vertices)
    if (!p.allFinite()) throw IoError(fmt::format("{}: a vertex has a coordinate that is not finite", path));
  write_file_atomically(path, format_msh(mesh, version, encoding));
}

}  // namespace metrica::io
