#include <metrica/bucket_cursors.hpp>
#include <metrica/classification.hpp>
#include <metrica/geometry.hpp>
#include <metrica/numbering.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace metrica {

void ValidationReport::add(const std::string& check, std::string message, std::size_t max_messages) {
  if (counts_[check]++ < max_messages) problems_.push_back({check, std::move(message)});
}

void ValidationReport::append(const ValidationReport& later, std::size_t max_messages) {
  std::map<std::string, std::size_t> kept;
  for (const Problem& p : later.problems_) {
    add(p.check, p.message, max_messages);
    ++kept[p.check];
  }
  for (const auto& [check, c] : later.counts_) counts_[check] += c - kept[check];
}

std::size_t ValidationReport::count(const std::string& check) const {
  const auto it = counts_.find(check);
  return it == counts_.end() ? 0 : it->second;
}

std::size_t ValidationReport::total() const {
  std::size_t n = 0;
  for (const auto& [check, c] : counts_) n += c;
  return n;
}

std::string ValidationReport::to_string() const {
  if (ok()) return "valid";
  std::string out;
  for (const auto& p : problems_) out += fmt::format("  [{}] {}\n", p.check, p.message);
  out += "invalid:";
  for (const auto& [check, c] : counts_) out += fmt::format(" {} {}", c, check);
  return out;
}

namespace {

class Checker {
 public:
  Checker(const Mesh& mesh, const ValidateOptions& opt) : m_(mesh), opt_(opt) {}

  ValidationReport run() {
    // Later checks assume vertex ids are sane; stop early if they are not.
    if (!check_vertices()) return std::move(report_);
    check_orientation();
    check_adjacency();
    check_faces_once();
    check_manifold();
    check_internal_manifold();
    check_classification();
    check_required();
    check_vert2tet();
    check_volume();
    return std::move(report_);
  }

 private:
  template <class... Args>
  void fail(const char* check, fmt::format_string<Args...> f, Args&&... args) {
    fail_in(report_, check, f, std::forward<Args>(args)...);
  }
  template <class... Args>
  void fail_in(ValidationReport& r, const char* check, fmt::format_string<Args...> f, Args&&... args) {
    r.add(check, fmt::format(f, std::forward<Args>(args)...), opt_.max_messages_per_check);
  }

  // check(t, report) for every live tet, on opt_.run's parts, each part
  // with its own report; the reports joined in tet order.
  template <class Check>
  void per_live_tet(Check&& check) {
    const std::size_t parts = std::max<std::size_t>(opt_.run.parts, 1);
    std::vector<ValidationReport> reports(parts);
    opt_.run(parts, [&](std::size_t p) {
      const auto [first, last] = part_slice(m_.tet_capacity(), parts, p);
      for (auto t = static_cast<TetId>(first); t < last; ++t)
        if (m_.tet_alive(t)) check(t, reports[p]);
    });
    for (const ValidationReport& r : reports) report_.append(r, opt_.max_messages_per_check);
  }

  bool check_vertices() {
    std::size_t live_v = 0;
    for (VertexId v = 0; v < m_.vertex_capacity(); ++v) live_v += m_.vertex_alive(v);
    if (live_v != m_.num_vertices())
      fail("vertices", "{} live vertices flagged, but the count says {}", live_v, m_.num_vertices());
    const std::size_t before = report_.total();
    per_live_tet([&](TetId t, ValidationReport& r) {
      const auto& tv = m_.tet(t);
      for (int i = 0; i < 4; ++i) {
        if (tv[i] >= m_.vertex_capacity() || !m_.vertex_alive(tv[i]))
          fail_in(r, "vertices", "tet {}: vertex {} ({}) is dead or out of range", numbered(t), i, numbered(tv[i]));
        for (int j = 0; j < i; ++j)
          if (tv[i] == tv[j]) fail_in(r, "vertices", "tet {}: vertex {} appears twice", numbered(t), numbered(tv[i]));
      }
    });
    std::size_t live_t = 0;
    for (TetId t = 0; t < m_.tet_capacity(); ++t) live_t += m_.tet_alive(t);
    if (live_t != m_.num_tets()) fail("vertices", "{} live tets found, but the count says {}", live_t, m_.num_tets());
    return report_.total() == before;
  }

  void check_orientation() {
    per_live_tet([&](TetId t, ValidationReport& r) {
      const auto& v = m_.tet(t);
      const double o = orient3d_fast(m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3]));
      if (!(o > 0))
        fail_in(r, "orientation", "tet {} ({} {} {} {}): orient3d = {:.3e} <= 0", numbered(t), numbered(v[0]),
                numbered(v[1]), numbered(v[2]), numbered(v[3]), o);
    });
  }

  void check_adjacency() {
    per_live_tet([&](TetId t, ValidationReport& r) {
      for (int f = 0; f < 4; ++f) {
        const FaceRef n = m_.neighbour(t, f);
        const SurfaceId s = m_.surface_id(t, f);
        if (!n.valid()) {
          if (s <= 0)
            fail_in(r, "boundary", "tet {} face {}: boundary face with surface id {} (must be > 0)", numbered(t), f, s);
          continue;
        }
        if (n.tet() >= m_.tet_capacity() || !m_.tet_alive(n.tet())) {
          fail_in(r, "adjacency", "tet {} face {}: neighbour tet {} is dead or out of range", numbered(t), f,
                  numbered(n.tet()));
          continue;
        }
        if (m_.neighbour(n) != FaceRef(t, f))
          fail_in(r, "adjacency", "tet {} face {} -> tet {} face {}, which does not point back", numbered(t), f,
                  numbered(n.tet()), n.face());
        else if (m_.internal_surface_id(t, f) != m_.internal_surface_id(n.tet(), n.face()))
          fail_in(r, "internal surface", "tet {} face {}: internal surface id {}, {} on the other side (tet {})",
                  numbered(t), f, m_.internal_surface_id(t, f), m_.internal_surface_id(n.tet(), n.face()),
                  numbered(n.tet()));
        else if (m_.tet_ref(t) != m_.tet_ref(n.tet()) && m_.internal_surface_id(t, f) == 0)
          fail_in(r, "internal surface", "tet {} face {}: between regions {} and {} without a surface id", numbered(t),
                  f, m_.tet_ref(t), m_.tet_ref(n.tet()));
        if (sorted(face_vertices(m_.tet(t), f)) != sorted(face_vertices(m_.tet(n.tet()), n.face())))
          fail_in(r, "adjacency", "tet {} face {} and tet {} face {} hold different vertices", t, f, n.tet(), n.face());
      }
    });
  }

  // Each triangle a face of one tet (boundary) or of two neighbours: a
  // third tet on it (tets that overlap, their adjacency consistent pair by
  // pair) is a mesh the other checks pass and no file can hold. The faces
  // once each (boundary faces, interior ones from the smaller tet id),
  // bucketed by their smallest vertex (a counting sort in the run's parts,
  // bucket_cursors); equal triangles meet in a bucket, the buckets checked
  // in parts of vertices whose reports join in vertex order.
  void check_faces_once() {
    const std::size_t nv = m_.vertex_capacity(), nt = m_.tet_capacity();
    const std::size_t parts = std::max<std::size_t>(opt_.run.parts, 1);
    auto each_face = [&](std::size_t t, auto&& f) {
      if (!m_.tet_alive(static_cast<TetId>(t))) return;
      for (int i = 0; i < 4; ++i) {
        const FaceRef n = m_.neighbour(static_cast<TetId>(t), i);
        if (!n.valid() || t < n.tet()) f(sorted(face_vertices(m_.tet(static_cast<TetId>(t)), i)));
      }
    };
    MeshArray<std::uint32_t> cursor, start;
    const std::size_t faces = bucket_cursors(
        nt, nv, parts, [&](std::size_t t, auto&& add) { each_face(t, [&](const TriangleVertices& k) { add(k[0]); }); },
        opt_.run, cursor, start);
    MeshArray<std::pair<VertexId, VertexId>> rest;
    rest.resize(faces);
    opt_.run(parts, [&](std::size_t p) {
      std::uint32_t* next = cursor.data() + p * nv;
      const auto [first, last] = part_slice(nt, parts, p);
      for (std::size_t t = first; t < last; ++t)
        each_face(t, [&](const TriangleVertices& k) { rest[next[k[0]]++] = {k[1], k[2]}; });
    });
    cursor = {};
    std::vector<ValidationReport> reports(parts);
    opt_.run(parts, [&](std::size_t p) {
      const auto [first, last] = part_slice(nv, parts, p);
      for (std::size_t v = first; v < last; ++v) {
        const auto bucket_begin = rest.begin() + start[v], bucket_end = rest.begin() + start[v + 1];
        std::sort(bucket_begin, bucket_end);
        for (auto it = std::adjacent_find(bucket_begin, bucket_end); it != bucket_end;
             it = std::adjacent_find(it + 1, bucket_end))
          fail_in(reports[p], "faces",
                  "triangle ({} {} {}) is a face of more than two tets, or of two that are not neighbours",
                  numbered(static_cast<VertexId>(v)), numbered(it->first), numbered(it->second));
      }
    });
    for (const ValidationReport& r : reports) report_.append(r, opt_.max_messages_per_check);
  }

  // Each boundary edge on exactly two boundary faces, and around each
  // boundary vertex the faces form a single closed umbrella.
  void check_manifold() {
    struct Link {
      VertexId center, a, b;
      bool operator<(const Link& o) const { return center < o.center; }
    };
    std::vector<std::uint64_t> edges;
    std::vector<Link> links;
    for_each_boundary_face(m_, [&](TetId t, int f) {
      const auto tri = face_vertices(m_.tet(t), f);
      for (int i = 0; i < 3; ++i) {
        edges.push_back(edge_key(tri[i], tri[(i + 1) % 3]));
        links.push_back({tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]});
      }
    });
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i != 2) {
        const auto e = edge_from_key(edges[i]);
        fail("manifold",
             "boundary edge ({} {}) lies on {} boundary faces (must be 2: the boundary is open or "
             "non-manifold)",
             e[0], e[1], j - i);
      }
      i = j;
    }
    std::stable_sort(links.begin(), links.end());
    std::vector<std::pair<VertexId, VertexId>> ring;
    for (std::size_t i = 0; i < links.size();) {
      std::size_t j = i;
      while (j < links.size() && links[j].center == links[i].center) ++j;
      // Follow a -> b around the center; one cycle must use every link.
      ring.clear();
      for (std::size_t k = i; k < j; ++k) ring.emplace_back(links[k].a, links[k].b);
      std::sort(ring.begin(), ring.end());
      bool ok = std::adjacent_find(ring.begin(), ring.end(), [](auto& x, auto& y) { return x.first == y.first; }) ==
                ring.end();
      if (ok) {
        VertexId at = ring[0].second;
        std::size_t steps = 1;
        while (at != ring[0].first && steps <= ring.size()) {
          auto it = std::lower_bound(ring.begin(), ring.end(), std::make_pair(at, VertexId{0}));
          if (it == ring.end() || it->first != at) break;
          at = it->second;
          ++steps;
        }
        ok = at == ring[0].first && steps == ring.size();
      }
      if (!ok)
        fail("manifold", "boundary vertex {}: its {} boundary faces do not form a single umbrella",
             numbered(links[i].center), j - i);
      i = j;
    }
  }

  // Each edge of an internal surface lies on at most two of its faces (one
  // at its border, where it meets another surface or ends inside a region).
  void check_internal_manifold() {
    if (!m_.has_internal_surfaces()) return;
    std::vector<std::pair<SurfaceId, std::uint64_t>> edges;
    for_each_surface_face(m_, [&](TetId t, int f) {
      if (!m_.neighbour(t, f).valid()) return;
      const auto tri = face_vertices(m_.tet(t), f);
      for (int i = 0; i < 3; ++i) edges.emplace_back(m_.internal_surface_id(t, f), edge_key(tri[i], tri[(i + 1) % 3]));
    });
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i > 2) {
        const auto e = edge_from_key(edges[i].second);
        fail("manifold", "edge ({} {}) lies on {} faces of internal surface {} (non-manifold)", numbered(e[0]),
             numbered(e[1]), j - i, edges[i].first);
      }
      i = j;
    }
  }

  void check_classification() {
    const auto c = compute_classification(m_, opt_.run);
    for (VertexId v = 0; v < m_.vertex_capacity(); ++v) {
      if (!m_.vertex_alive(v)) continue;
      if (c.vertex_class[v] != m_.vertex_class(v))
        fail("classification", "vertex {}: classified {}, should be {}", numbered(v),
             metrica::to_string(m_.vertex_class(v)), metrica::to_string(c.vertex_class[v]));
      const bool internal = !c.on_internal_surface.empty() && c.on_internal_surface[v];
      if (internal != m_.on_internal_surface(v))
        fail("classification", "vertex {}: {} an internal surface, marked otherwise", numbered(v),
             internal ? "on" : "not on");
    }
    for (auto key : c.ridges)
      if (!m_.ridge_edges().count(key)) {
        const auto e = edge_from_key(key);
        fail("classification", "edge ({} {}) is a ridge but not marked", numbered(e[0]), numbered(e[1]));
      }
    for (auto key : m_.ridge_edges())
      if (!c.ridges.count(key)) {
        const auto e = edge_from_key(key);
        fail("classification", "edge ({} {}) is marked as a ridge but is not one", numbered(e[0]), numbered(e[1]));
      }
  }

  // Required triangles are surface faces and required edges edges of the
  // mesh, all of their vertices required.
  void check_required() {
    const auto triangles = m_.required_triangles();
    const auto& edges = m_.required_edges();
    if (triangles.empty() && edges.empty()) return;
    std::vector<TriangleVertices> faces;
    std::unordered_set<std::uint64_t> tet_edges;
    for (TetId t = 0; t < m_.tet_capacity(); ++t) {
      if (!m_.tet_alive(t)) continue;
      const auto& v = m_.tet(t);
      for (int f = 0; f < 4; ++f)
        if (m_.is_surface_face(t, f)) {
          TriangleVertices key = face_vertices(v, f);
          std::sort(key.begin(), key.end());
          faces.push_back(key);
        }
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if (m_.is_required(v[i]) && m_.is_required(v[j])) tet_edges.insert(edge_key(v[i], v[j]));
    }
    std::sort(faces.begin(), faces.end());
    for (const auto& tri : triangles) {
      if (!std::binary_search(faces.begin(), faces.end(), tri))
        fail("required", "required triangle ({} {} {}) is not a surface face", numbered(tri[0]), numbered(tri[1]),
             numbered(tri[2]));
    }
    for (auto key : edges) {
      const auto e = edge_from_key(key);
      if (!tet_edges.count(key))
        fail("required", "required edge ({} {}) is not an edge of the mesh, or an end is not required", numbered(e[0]),
             numbered(e[1]));
    }
  }

  void check_vert2tet() {
    for (VertexId v = 0; v < m_.vertex_capacity(); ++v) {
      if (!m_.vertex_alive(v)) continue;
      const TetId t = m_.vert2tet(v);
      if (t >= m_.tet_capacity() || !m_.tet_alive(t))
        fail("vert2tet", "vertex {}: hint {} is not a live tet", numbered(v), numbered(t));
      else if (local_index(m_.tet(t), v) < 0)
        fail("vert2tet", "vertex {}: hint tet {} does not contain it", numbered(v), numbered(t));
    }
  }

  void check_volume() {
    if (!opt_.expected_volume) return;
    const double expected = *opt_.expected_volume, actual = m_.volume();
    if (!(std::abs(actual - expected) <= opt_.volume_tolerance * std::abs(expected)))
      fail("volume", "volume {:.17g} differs from the expected {:.17g} (relative {:.2e})", actual, expected,
           std::abs(actual - expected) / std::abs(expected));
  }

  const Mesh& m_;
  const ValidateOptions& opt_;
  ValidationReport report_;
};

}  // namespace

ValidationReport validate(const Mesh& mesh, const ValidateOptions& options) { return Checker(mesh, options).run(); }

ValidationReport Mesh::validate(const ValidateOptions& options) const { return metrica::validate(*this, options); }
ValidationReport Mesh::validate() const { return metrica::validate(*this, ValidateOptions{}); }

}  // namespace metrica
