// Where a new or moved vertex gets its metric (seed, section 3.2):
//  - an analytic metric, evaluated at its position (the UGAWG cases are
//    defined by such functions);
//  - the user's field kept as a background (a metric from a file or from
//    arrays: background_metric.hpp), interpolated at its position, the walk
//    starting from the background tet of a vertex it is made from;
//  - neither: the Space policy interpolates the vertices it is made from
//    (a moved vertex keeps its metric).
#pragma once

#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <cstddef>
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

// An analytic metric, a background, or none (interpolation). Made from
// either pointer; an empty function counts as none.
struct MetricSource {
  const MetricFunction* exact = nullptr;
  const BackgroundMetric* background = nullptr;

  MetricSource() = default;
  MetricSource(std::nullptr_t) {}                                                    // NOLINT: implicit
  MetricSource(const MetricFunction* f) : exact(f != nullptr && *f ? f : nullptr) {}  // NOLINT: implicit
  MetricSource(const BackgroundMetric* b) : background(b) {}                        // NOLINT: implicit

  // True when vertices take the metric at their position.
  explicit operator bool() const { return exact != nullptr || background != nullptr; }

  // The metric at p of a vertex made from (or, moved: being) `from`; only
  // when the source is set.
  VertexMetric at(const Mesh& mesh, const Point& p, std::span<const VertexId> from) const {
    if (exact != nullptr) {
      const Sym6 m = (*exact)(p);
      return {m, spd_log(m)};
    }
    TetId start = kNoId;
    for (std::size_t i = 0; i < from.size() && start == kNoId; ++i) start = mesh.background_tet(from[i]);
    return background->at(p, start).metric;
  }
};

template <MetricSpace S>
VertexMetric new_vertex_metric(const Mesh& mesh, const MetricSource& source, std::span<const VertexId> ids,
                               std::span<const double> w, const Point& p) {
  if (source) return source.at(mesh, p, ids);
  return S::interpolate(mesh, ids, w);
}

}  // namespace metrica
