#include <metrica/classification.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/numbering.hpp>
#include <metrica/vertex_tets.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <set>

namespace metrica {
namespace {

// Checks orientation; reorients every tet when all are negative.
std::vector<TetVertices> oriented_tets(const io::MeshData& d, const std::string& source) {
  std::vector<TetVertices> tets = d.tets;
  std::size_t negative = 0;
  std::vector<std::string> bad;
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const auto& t = tets[i];
    const bool repeated = t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] || t[2] == t[3];
    const double o =
        repeated ? 0.0 : orient3d_fast(d.vertices[t[0]], d.vertices[t[1]], d.vertices[t[2]], d.vertices[t[3]]);
    if (o < 0) ++negative;
    if (o == 0 && bad.size() < 5)
      bad.push_back(fmt::format("tet {} (vertices {} {} {} {}) is degenerate (zero volume)", numbered(i),
                                numbered(t[0]), numbered(t[1]), numbered(t[2]), numbered(t[3])));
  }
  if (negative == tets.size()) {
    log::warn("{}: every tet is negatively oriented; reorienting all {} tets", source, tets.size());
    for (auto& t : tets) std::swap(t[2], t[3]);
  } else if (negative > 0) {
    for (std::size_t i = 0; i < tets.size() && bad.size() < 5; ++i) {
      const auto& t = tets[i];
      if (orient3d_fast(d.vertices[t[0]], d.vertices[t[1]], d.vertices[t[2]], d.vertices[t[3]]) < 0)
        bad.push_back(fmt::format("tet {} (vertices {} {} {} {}) is inverted", numbered(i), numbered(t[0]),
                                  numbered(t[1]), numbered(t[2]), numbered(t[3])));
    }
  }
  if (!bad.empty() || (negative > 0 && negative < tets.size())) {
    std::string msg = fmt::format("{}: invalid input tetrahedra ({} inverted of {}):", source, negative, tets.size());
    for (const auto& b : bad) msg += "\n  " + b;
    throw InputError(msg);
  }
  return tets;
}

struct FaceKeyed {
  TriangleVertices key;
  std::uint32_t index;
};

}  // namespace

Mesh build_mesh(const io::MeshData& d, const BuildOptions& opt) {
  const std::string& src = opt.source;
  if (d.tets.empty()) throw InputError(fmt::format("{}: the mesh has no tetrahedra", src));
  const auto tets = oriented_tets(d, src);
  const std::size_t nv = d.vertices.size();

  Mesh mesh;
  mesh.reserve(nv, tets.size());
  for (std::size_t v = 0; v < nv; ++v) mesh.add_vertex(d.vertices[v], v < d.vertex_refs.size() ? d.vertex_refs[v] : 0);
  for (std::size_t t = 0; t < tets.size(); ++t) mesh.add_tet(tets[t], t < d.tet_refs.size() ? d.tet_refs[t] : 0);

  const VertexTets incidence(mesh);
  std::size_t unused = 0;
  for (VertexId v = 0; v < nv; ++v) {
    if (incidence.of(v).empty()) {
      mesh.remove_vertex(v);
      ++unused;
    } else {
      mesh.set_vert2tet(v, incidence.of(v)[0]);
    }
  }
  if (unused > 0) log::warn("{}: {} vertices belong to no tetrahedron and are dropped", src, unused);

  // Face adjacency: the tets sharing a face all contain its first vertex.
  for (TetId t = 0; t < tets.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f).valid()) continue;
      const auto face = face_vertices(tets[t], f);
      FaceRef match;
      for (TetId u : incidence.of(face[0])) {
        if (u == t) continue;
        const auto& tu = tets[u];
        const int ib = local_index(tu, face[1]), ic = local_index(tu, face[2]);
        if (ib < 0 || ic < 0) continue;
        const int ia = local_index(tu, face[0]);
        const int g = 6 - ia - ib - ic;  // the remaining local index
        if (match.valid())
          throw InputError(fmt::format("{}: face ({} {} {}) is shared by more than two tetrahedra (tets {}, {}, {})",
                                       src, numbered(face[0]), numbered(face[1]), numbered(face[2]), numbered(t),
                                       numbered(match.tet()), numbered(u)));
        match = FaceRef(u, g);
      }
      // A third tet on this face would have been found above, when the
      // first of the three was processed, so `match` is still unlinked.
      if (match.valid()) mesh.link(FaceRef(t, f), match);
    }
  }

  // Boundary faces take the surface id of the input triangle covering them.
  std::vector<FaceKeyed> triangles(d.triangles.size());
  SurfaceId max_id = 0;
  for (std::size_t i = 0; i < d.triangles.size(); ++i) {
    triangles[i] = {sorted(d.triangles[i]), static_cast<std::uint32_t>(i)};
    if (i < d.triangle_refs.size()) max_id = std::max(max_id, d.triangle_refs[i]);
  }
  std::sort(triangles.begin(), triangles.end(), [](const FaceKeyed& a, const FaceKeyed& b) {
    return a.key < b.key || (a.key == b.key && a.index < b.index);
  });
  // Up to kMaxSurfaceId - 1, so that the default id (the largest + 1) fits.
  if (max_id >= kMaxSurfaceId || opt.default_surface_id >= kMaxSurfaceId)
    throw InputError(fmt::format("{}: surface id {} is beyond the ids a mesh holds (1 to {})", src,
                                 std::max(max_id, opt.default_surface_id), kMaxSurfaceId - 1));
  const SurfaceId default_id = opt.default_surface_id > 0 ? opt.default_surface_id : max_id + 1;
  std::vector<char> used(d.triangles.size(), 0);
  std::size_t untagged = 0, nonpositive = 0, boundary_faces = 0;
  std::set<int> outer_ids;  // the ids the input gave to outer boundary faces
  for (TetId t = 0; t < tets.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f).valid()) continue;
      ++boundary_faces;
      const auto key = sorted(face_vertices(tets[t], f));
      auto it = std::lower_bound(triangles.begin(), triangles.end(), key,
                                 [](const FaceKeyed& a, const TriangleVertices& k) { return a.key < k; });
      SurfaceId id = default_id;
      if (it != triangles.end() && it->key == key) {
        const int ref = it->index < d.triangle_refs.size() ? d.triangle_refs[it->index] : 0;
        if (ref > 0) {
          id = ref;
          outer_ids.insert(ref);
        } else
          ++nonpositive;
        for (auto jt = it; jt != triangles.end() && jt->key == key; ++jt) used[jt->index] = 1;
      } else {
        ++untagged;
      }
      mesh.set_surface_id(t, f, id);
    }
  }
  if (untagged > 0 && opt.require_boundary_triangles && untagged < boundary_faces)
    throw InputError(
        fmt::format("{}: {} boundary faces have no input triangle: give the whole boundary as Triangles "
                    "with surface ids (their edges between ids become ridges)",
                    src, untagged));
  // The faces no triangle covers, or a boundary of one id, are split by
  // angle (unless the ridge angle is 180 or more); with
  // split_every_surface every surface is. Without it, a mesh with CAD
  // association records keeps its ids: they are the model's surfaces, and
  // its curves the ridges.
  const bool on_model = !d.on_geometry[0].empty() || !d.on_geometry[1].empty() || !d.on_geometry[2].empty();
  std::vector<SurfaceId> split;
  if (opt.ridge_angle < 180.0 && (!on_model || opt.split_every_surface)) {
    if (opt.split_every_surface) {
      split.assign(outer_ids.begin(), outer_ids.end());
      if (untagged > 0 || nonpositive > 0) split.push_back(default_id);
    } else if (untagged > 0 || nonpositive > 0) {
      split.push_back(default_id);
    } else if (outer_ids.size() == 1) {
      split.push_back(*outer_ids.begin());
    }
  }
  if (!split.empty()) untagged = nonpositive = 0;  // said at the end, with what the split found
  if (untagged > 0 && !opt.untagged_expected)
    log::warn("{}: {} boundary faces have no input triangle; they get surface id {}", src, untagged, default_id);
  if (nonpositive > 0)
    log::warn("{}: {} boundary triangles have a reference <= 0; they get surface id {}", src, nonpositive, default_id);

  // Internal surfaces: a triangle on a face with a tet on both sides, and
  // every face between two regions (tet refs), which takes the default id
  // when no triangle covers it.
  std::size_t between_regions_untagged = 0;
  for (std::size_t i = 0; i < d.triangles.size(); ++i) {
    if (used[i]) continue;
    const auto& tri = d.triangles[i];
    FaceRef face;
    const bool distinct = tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2];
    for (TetId u : distinct ? incidence.of(tri[0]) : std::span<const TetId>{}) {
      const int ib = local_index(tets[u], tri[1]), ic = local_index(tets[u], tri[2]);
      if (ib >= 0 && ic >= 0) face = FaceRef(u, 6 - local_index(tets[u], tri[0]) - ib - ic);
    }
    if (!face.valid())
      throw InputError(fmt::format("{}: triangle {} (vertices {} {} {}) is not a face of any tetrahedron", src,
                                   numbered(i), numbered(tri[0]), numbered(tri[1]), numbered(tri[2])));
    const int ref = i < d.triangle_refs.size() ? d.triangle_refs[i] : 0;
    const SurfaceId id = ref > 0 ? ref : default_id;
    const FaceRef other = mesh.neighbour(face);
    if (!other.valid()) continue;  // a boundary face given twice
    const SurfaceId before = mesh.internal_surface_id(face.tet(), face.face());
    if (before != 0 && before != id)
      throw InputError(fmt::format("{}: triangle {} (vertices {} {} {}) is given twice, with surface ids {} and {}",
                                   src, numbered(i), numbered(tri[0]), numbered(tri[1]), numbered(tri[2]), before, id));
    if (ref > 0 && outer_ids.count(ref))
      throw InputError(
          fmt::format("{}: triangle {} (vertices {} {} {}) lies inside the volume with surface id {}, "
                      "which triangles on the outer boundary have too: an internal surface needs ids "
                      "of its own",
                      src, numbered(i), numbered(tri[0]), numbered(tri[1]), numbered(tri[2]), id));
    mesh.set_internal_surface_id(face.tet(), face.face(), id);
    mesh.set_internal_surface_id(other.tet(), other.face(), id);
  }
  for (TetId t = 0; t < tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      const FaceRef n = mesh.neighbour(t, f);
      if (!n.valid() || n.tet() < t || mesh.tet_ref(n.tet()) == mesh.tet_ref(t)) continue;
      if (mesh.internal_surface_id(t, f) != 0) continue;
      mesh.set_internal_surface_id(t, f, default_id);
      mesh.set_internal_surface_id(n.tet(), n.face(), default_id);
      ++between_regions_untagged;
    }
  if (between_regions_untagged > 0)
    log::warn("{}: {} faces between two regions have no input triangle; they get surface id {}", src,
              between_regions_untagged, default_id);

  for (const auto& e : d.edges) mesh.add_feature_edge(e[0], e[1]);
  for (VertexId v : d.corners) mesh.set_required(v, true);
  for (VertexId v : d.required_vertices) mesh.set_required(v, true);
  // Required edges must be edges of the mesh; required triangles are among
  // the triangles, each matched to a face above.
  for (std::size_t i = 0; i < d.required_edges.size(); ++i) {
    const auto& e = d.edges[d.required_edges[i]];
    bool found = false;
    for (TetId u : incidence.of(e[0])) found = found || (e[0] != e[1] && local_index(tets[u], e[1]) >= 0);
    if (!found)
      throw InputError(fmt::format("{}: required edge {} (edge {}, vertices {} {}) is not an edge of any tetrahedron",
                                   src, numbered(i), numbered(d.required_edges[i]), numbered(e[0]), numbered(e[1])));
    mesh.add_required_edge(e[0], e[1]);
  }
  std::vector<TriangleVertices> required;
  required.reserve(d.required_triangles.size());
  for (std::uint32_t i : d.required_triangles) required.push_back(d.triangles[i]);
  mesh.add_required_triangles(required);
  mesh.classify();
  if (!split.empty()) {
    const AngleSplit a = split_surfaces_at_angle(mesh, opt.ridge_angle, split);
    if (!opt.untagged_expected) {
      std::size_t corners = 0;
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
        corners += mesh.vertex_alive(v) && mesh.vertex_class(v) == VertexClass::corner;
      log::emit(
          log::Level::normal,
          fmt::format("{}: {} split at edges sharper than {:g} degrees: {} surfaces, {} ridge edges, {} corners", src,
                      split.size() == 1 && split[0] == default_id ? "the boundary without surface ids"
                      : opt.split_every_surface                   ? "every surface"
                                                                  : "the boundary's one surface",
                      opt.ridge_angle, a.surfaces, mesh.ridge_edges().size(), corners));
    }
  }
  return mesh;
}

io::MeshData extract_mesh_data(const Mesh& mesh) {
  io::MeshData d;
  // Sized once: grown by doubling, the copy of a 4M-tet mesh took twice
  // its size at the end of a run.
  d.vertices.reserve(mesh.num_vertices());
  d.vertex_refs.reserve(mesh.num_vertices());
  d.tets.reserve(mesh.num_tets());
  d.tet_refs.reserve(mesh.num_tets());
  std::vector<VertexId> new_id(mesh.vertex_capacity(), kNoId);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    new_id[v] = static_cast<VertexId>(d.vertices.size());
    d.vertices.push_back(mesh.point(v));
    d.vertex_refs.push_back(mesh.vertex_ref(v));
    if (mesh.vertex_class(v) == VertexClass::corner) d.corners.push_back(new_id[v]);
    if (mesh.is_required(v)) d.required_vertices.push_back(new_id[v]);
    if (mesh.has_geo_params() && mesh.geo_param(v).valid()) {
      const GeoParam& g = mesh.geo_param(v);
      d.on_geometry[static_cast<std::size_t>(g.dim)].push_back({new_id[v], g.tag, g.u, g.v, 0.0});
    }
  }
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& tv = mesh.tet(t);
    d.tets.push_back({new_id[tv[0]], new_id[tv[1]], new_id[tv[2]], new_id[tv[3]]});
    d.tet_refs.push_back(mesh.tet_ref(t));
    for (int f = 0; f < 4; ++f) {
      // Boundary faces, and each internal-surface face once (from the
      // smaller tet id).
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid() && (mesh.internal_surface_id(t, f) == 0 || n.tet() < t)) continue;
      const auto tri = face_vertices(tv, f);
      d.triangles.push_back({new_id[tri[0]], new_id[tri[1]], new_id[tri[2]]});
      d.triangle_refs.push_back(mesh.face_surface_id(t, f));
    }
  }
  std::vector<std::uint64_t> ridges(mesh.ridge_edges().begin(), mesh.ridge_edges().end());
  std::sort(ridges.begin(), ridges.end());
  for (auto key : ridges) {
    const auto e = edge_from_key(key);
    d.ridges.push_back(static_cast<std::uint32_t>(d.edges.size()));
    d.edges.push_back({new_id[e[0]], new_id[e[1]]});
    d.edge_refs.push_back(0);
  }
  // Required edges: a ridge's index, or an edge of their own after them.
  std::vector<std::uint64_t> required(mesh.required_edges().begin(), mesh.required_edges().end());
  std::sort(required.begin(), required.end());
  for (auto key : required) {
    const auto at = std::lower_bound(ridges.begin(), ridges.end(), key);
    if (at != ridges.end() && *at == key) {
      d.required_edges.push_back(static_cast<std::uint32_t>(at - ridges.begin()));
      continue;
    }
    const auto e = edge_from_key(key);
    d.required_edges.push_back(static_cast<std::uint32_t>(d.edges.size()));
    d.edges.push_back({new_id[e[0]], new_id[e[1]]});
    d.edge_refs.push_back(0);
  }
  // Required triangles: found among the surface triangles by their sorted
  // vertex ids (the mesh's ids, before renumbering).
  const auto req = mesh.required_triangles();
  if (!req.empty()) {
    std::vector<VertexId> old_id(d.vertices.size());
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      if (new_id[v] != kNoId) old_id[new_id[v]] = v;
    for (std::size_t i = 0; i < d.triangles.size(); ++i) {
      TriangleVertices key{old_id[d.triangles[i][0]], old_id[d.triangles[i][1]], old_id[d.triangles[i][2]]};
      std::sort(key.begin(), key.end());
      if (std::binary_search(req.begin(), req.end(), key))
        d.required_triangles.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return d;
}

}  // namespace metrica
