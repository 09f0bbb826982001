#include <metrica/classification.hpp>
#include <metrica/geometry.hpp>
#include <metrica/mesh_summary.hpp>

#include <algorithm>
#include <limits>

namespace metrica {

MeshSummary summarize(const Mesh& m) {
  MeshSummary s;
  s.vertices = m.num_vertices();
  s.tets = m.num_tets();
  const auto box = bounding_box(m);
  s.lo = box.lo;
  s.hi = box.hi;
  for (VertexId v = 0; v < m.vertex_capacity(); ++v) {
    if (!m.vertex_alive(v)) continue;
    s.required_vertices += m.is_required(v);
    switch (m.vertex_class(v)) {
      case VertexClass::interior: ++s.interior_vertices; break;
      case VertexClass::surface: ++s.surface_vertices; break;
      case VertexClass::ridge: ++s.ridge_vertices; break;
      case VertexClass::corner: ++s.corners; break;
    }
  }
  s.min_tet_volume = std::numeric_limits<double>::max();
  s.max_tet_volume = -s.min_tet_volume;
  for (TetId t = 0; t < m.tet_capacity(); ++t) {
    if (!m.tet_alive(t)) continue;
    const auto& v = m.tet(t);
    const double vol = tet_volume(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
    s.volume += vol;
    s.min_tet_volume = std::min(s.min_tet_volume, vol);
    s.max_tet_volume = std::max(s.max_tet_volume, vol);
    auto& region = s.regions[m.tet_ref(t)];
    ++region.tets;
    region.volume += vol;
  }
  for_each_surface_face(m, [&](TetId t, int f) {
    const bool internal = m.neighbour(t, f).valid();
    ++(internal ? s.internal_faces : s.boundary_faces);
    const auto tri = face_vertices(m.tet(t), f);
    auto& surf = s.surfaces[m.face_surface_id(t, f)];
    ++surf.faces;
    surf.internal = surf.internal || internal;
    surf.area += triangle_area(m.point(tri[0]), m.point(tri[1]), m.point(tri[2]));
  });
  s.ridge_edges = m.ridge_edges().size();
  s.ridge_curves = count_ridge_curves(m);
  return s;
}

}  // namespace metrica
