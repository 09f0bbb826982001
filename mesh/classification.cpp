#include <metrica/classification.hpp>

#include <algorithm>
#include <numeric>

namespace metrica {
namespace {

struct EdgeSide {
  std::uint64_t key;
  SurfaceId surface;
  bool operator<(const EdgeSide& o) const { return key < o.key || (key == o.key && surface < o.surface); }
};

// The class of a boundary vertex on `degree` ridge edges, `pair_changes`
// when they lie between different pairs of surfaces.
VertexClass boundary_class(unsigned degree, bool pair_changes, bool corner_anyway) {
  if (corner_anyway || degree == 1 || degree >= 3 || pair_changes) return VertexClass::corner;
  return degree == 2 ? VertexClass::ridge : VertexClass::surface;
}

std::uint64_t surface_pair(SurfaceId lo, SurfaceId hi) {
  return (std::uint64_t(std::uint32_t(lo)) << 32) | std::uint32_t(hi);
}

}  // namespace

Classification compute_classification(const Mesh& mesh, const PartRunner& run) {
  Classification c;
  c.vertex_class.assign(mesh.vertex_capacity(), VertexClass::interior);

  // The surface faces, found in the run's parts (the one sweep over every
  // tet), then taken in tet order.
  const std::size_t parts = std::max<std::size_t>(run.parts, 1);
  std::vector<std::vector<std::pair<TetId, int>>> found(parts);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(mesh.tet_capacity(), parts, p);
    for_each_surface_face_in(mesh, first, last, [&](TetId t, int f) { found[p].emplace_back(t, f); });
  });

  // Every surface face contributes its three edges with its surface id.
  if (mesh.has_internal_surfaces()) c.on_internal_surface.assign(mesh.vertex_capacity(), 0);
  std::vector<EdgeSide> sides;
  for (const auto& part : found)
    for (const auto& [t, f] : part) {
      const auto tri = face_vertices(mesh.tet(t), f);
      const SurfaceId s = mesh.face_surface_id(t, f);
      const bool internal = mesh.neighbour(t, f).valid();
      for (int i = 0; i < 3; ++i) {
        sides.push_back({edge_key(tri[i], tri[(i + 1) % 3]), s});
        c.vertex_class[tri[i]] = VertexClass::surface;
        if (internal) c.on_internal_surface[tri[i]] = 1;
      }
    }
  std::sort(sides.begin(), sides.end());

  // Per vertex: number of ridge edges, and the surface pair of the first.
  std::vector<std::uint8_t> degree(mesh.vertex_capacity(), 0);
  std::vector<std::uint64_t> first_pair(mesh.vertex_capacity(), 0);
  std::vector<std::uint8_t> pair_changes(mesh.vertex_capacity(), 0);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    const SurfaceId lo = sides[i].surface, hi = sides[j - 1].surface;
    const bool ridge = lo != hi || mesh.feature_edges().count(sides[i].key) != 0;
    if (ridge) {
      c.ridges.insert(sides[i].key);
      const std::uint64_t pair = surface_pair(lo, hi);
      for (VertexId v : edge_from_key(sides[i].key)) {
        if (degree[v] == 0)
          first_pair[v] = pair;
        else if (first_pair[v] != pair)
          pair_changes[v] = 1;
        if (degree[v] < 255) ++degree[v];
      }
    }
    i = j;
  }

  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v) || c.vertex_class[v] == VertexClass::interior) continue;
    // A vertex at a model vertex (a CAD model's corner, even where the
    // mesh sees no ridge: a closed curve's seam point) stays a corner.
    const bool model_corner = mesh.has_geo_params() && mesh.geo_param(v).valid() && mesh.geo_param(v).dim == 0;
    c.vertex_class[v] = boundary_class(degree[v], pair_changes[v] != 0, mesh.is_required(v) || model_corner);
  }
  return c;
}

VertexClass vertex_class_of_fan(std::span<FanSide> sides) {
  std::sort(sides.begin(), sides.end());
  unsigned degree = 0;
  bool pair_changes = false;
  std::uint64_t first_pair = 0;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].other == sides[i].other) ++j;
    const SurfaceId lo = sides[i].surface, hi = sides[j - 1].surface;
    if (lo != hi) {
      const std::uint64_t pair = surface_pair(lo, hi);
      if (degree == 0)
        first_pair = pair;
      else if (first_pair != pair)
        pair_changes = true;
      ++degree;
    }
    i = j;
  }
  return sides.empty() ? VertexClass::interior : boundary_class(degree, pair_changes, false);
}

void Mesh::classify() {
  auto c = compute_classification(*this);
  vertex_class_.assign(c.vertex_class.begin(), c.vertex_class.end());
  edge_tags_.set_ridges(std::move(c.ridges));
  for (VertexId v = 0; v < vertex_capacity(); ++v)
    set_on_internal_surface(v, !c.on_internal_surface.empty() && c.on_internal_surface[v]);
}

std::size_t count_ridge_curves(const Mesh& mesh) {
  // Union-find over ridge edges, joined at ridge (non-corner) vertices.
  std::vector<std::uint64_t> edges(mesh.ridge_edges().begin(), mesh.ridge_edges().end());
  std::sort(edges.begin(), edges.end());
  std::vector<std::size_t> parent(edges.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::size_t> edge_at(mesh.vertex_capacity(), SIZE_MAX);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (VertexId v : edge_from_key(edges[i])) {
      if (mesh.vertex_class(v) == VertexClass::corner) continue;
      if (edge_at[v] == SIZE_MAX)
        edge_at[v] = i;
      else
        parent[find(i)] = find(edge_at[v]);
    }
  }
  std::size_t curves = 0;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (find(i) == i) ++curves;
  return curves;
}

}  // namespace metrica
