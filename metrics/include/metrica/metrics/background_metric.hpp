// The user's metric as the background of an adaptation: the mesh the
// metric was given on and its tensors, kept read-only for the whole run,
// so that the field the mesh is adapted to (and measured in) stays the
// one the user gave, however many times vertices are made and moved.
//
// A point takes the log-Euclidean P1 interpolation of the background,
// exp(sum_i l_i log M_i) over the background tet that holds it, l_i its
// barycentric coordinates there (seed, eq. (metric_interpolation)). The
// tet is found by walking from a start (the background tet of a vertex it
// is made from, Mesh::background_tet), with PointLocator's grid when the
// walk is blocked. A point outside the background (a curved wall placed on
// the model beyond the input's facets) takes the nearest tet's value with
// its coordinates clamped. Nothing is written after construction: any
// number of threads may sample at once.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/part_runner.hpp>
#include <metrica/point_location.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace metrica {

class BackgroundMetric {
 public:
  // A copy of `mesh`'s points and cells and the logarithms of `metric`
  // (one SPD tensor per vertex id; InputError otherwise).
  BackgroundMetric(const Mesh& mesh, std::span<const Sym6> metric);
  // The same with the mesh's own metric.
  explicit BackgroundMetric(const Mesh& mesh);
  BackgroundMetric(const BackgroundMetric&) = delete;
  BackgroundMetric& operator=(const BackgroundMetric&) = delete;

  struct Sample {
    VertexMetric metric;  // metric.background: the tet it was found in
    bool inside = true;   // false: p lies outside the background (clamped)
  };
  // The metric at p, the walk starting at background tet `start` (kNoId:
  // anywhere).
  Sample at(const Point& p, TetId start = kNoId) const;

  // Makes `mesh` ready to take metrics from here (its metrics are left as
  // they are): its background tets are enabled and each vertex gets the
  // tet holding it (its own incident tet for a vertex where the background
  // has one at the same point: the mesh the background was made from),
  // whatever tets of another background it held. Outside parallel passes.
  void attach(Mesh& mesh) const;

  // Every live vertex of `mesh` takes the background's metric at its
  // position (its own background tet starting the walk, else the previous
  // vertex's of its part); the mesh's background tets are enabled and set.
  // The vertices are cut into run.parts parts, located concurrently.
  // Returns the number of vertices outside the background. Outside
  // parallel passes.
  std::size_t assign(Mesh& mesh, const PartRunner& run = {}) const;

  const Mesh& mesh() const { return mesh_; }

 private:
  Mesh mesh_;
  std::vector<Sym6> log_metric_;
  PointLocator locator_;  // over mesh_
};

}  // namespace metrica
