// Where a new or moved vertex gets its metric: interpolated by the Space
// policy from the vertices it is made from, or, when the user gives one,
// evaluated from an analytic metric at its position (seed, section 3.2;
// the UGAWG cases are defined by such functions).
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <functional>

namespace metrica {

using MetricFunction = std::function<Sym6(const Point&)>;

// `metric` evaluated at every vertex of the mesh.
inline void assign_metric(Mesh& mesh, const MetricFunction& metric) {
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) {
      const Sym6 m = metric(mesh.point(v));
      mesh.set_metric(v, m, spd_log(m));
    }
  mesh.clear_quality_cache();  // every tet's quality changed
}

template <MetricSpace S>
VertexMetric new_vertex_metric(const Mesh& mesh, const MetricFunction* exact, std::span<const VertexId> ids,
                               std::span<const double> w, const Point& p) {
  if (exact != nullptr && *exact) {
    const Sym6 m = (*exact)(p);
    return {m, spd_log(m)};
  }
  return S::interpolate(mesh, ids, w);
}

}  // namespace metrica
