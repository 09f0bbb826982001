// Point creation by edges: every edge longer than max_length (sqrt 2 by
// default) in the metric is split at its metric midpoint, longest first.
// Proximity filter: a new point closer than min_new_distance (in the
// metric) to a point created earlier in the same pass and joined to it by
// an edge waits for the next pass. Each split locks the vertices of its
// shell, the unit of work a thread owns under Speculative.
#pragma once

#include <metrica/operators/edge_queue.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operator_stats.hpp>
#include <metrica/operators/split_edge.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace metrica {

struct RefineOptions {
  double max_length = std::sqrt(2.0);
  double min_new_distance = 1.0 / std::sqrt(2.0);
  // When set, new vertices take this metric instead of an interpolated one.
  const MetricFunction* metric = nullptr;
};

// The parameter t in [0,1] of the point of ab at equal metric distance from
// a and b when the length grows geometrically from la (at a) to lb (at b),
// as the UGAWG length assumes: la ((lb/la)^t - 1) / ln(lb/la) is half of
// the total.
inline double metric_midpoint(double la, double lb) {
  const double r = lb / la;
  if (std::abs(r - 1.0) < 1e-6) return 0.5;
  return std::log(0.5 * (r + 1.0)) / std::log(r);
}

template <MetricSpace S, Precision P, Concurrency C>
OperatorStats refine_edges(Mesh& mesh, const RefineOptions& o = {}) {
  Stopwatch clock;
  OperatorStats stats;
  const auto todo = edges_beyond<S>(mesh, o.max_length, EdgeOrder::longest_first);
  std::vector<std::uint8_t> touched(mesh.vertex_capacity(), 0);
  TetList ball;
  Shell shell;
  VertexList cavity;
  typename C::Locks locks;
  for (const auto& c : todo) {
    ++stats.tried;
    vertex_ball(mesh, c.a, ball);
    if (!edge_shell(mesh, c.a, c.b, ball, shell)) continue;
    cavity.clear();
    append_vertices(mesh, shell.tets, cavity);
    if (!locks.acquire(std::span<const VertexId>(cavity.data(), cavity.size()))) {
      ++stats.conflicts;
      continue;
    }
    const Eigen::Vector3d e = mesh.point(c.b) - mesh.point(c.a);
    const auto& ma = S::vertex_metric(mesh, c.a);
    const auto& mb = S::vertex_metric(mesh, c.b);
    const double t = metric_midpoint(std::sqrt(metric_norm2(ma, e)), std::sqrt(metric_norm2(mb, e)));
    const Point p = mesh.point(c.a) + t * e;
    bool crowded = false;
    for (VertexId v : cavity) {
      if (v >= touched.size() || !touched[v]) continue;
      const auto& mv = S::vertex_metric(mesh, v);
      const Eigen::Vector3d d = p - mesh.point(v);
      crowded = crowded || std::sqrt(metric_norm2(mv, d)) < o.min_new_distance;
    }
    if (crowded) {
      ++stats.deferred;
      locks.release();
      continue;
    }
    if (!split_is_valid<P>(mesh, shell, c.a, c.b, p)) {
      ++stats.rejected;
      locks.release();
      continue;
    }
    const std::array<VertexId, 2> ends{c.a, c.b};
    const std::array<double, 2> w{1.0 - t, t};
    const VertexMetric m = new_vertex_metric<S>(mesh, o.metric, ends, w, p);
    const VertexId n = split_edge(mesh, shell, c.a, c.b, p, m);
    locks.release();
    ++stats.applied;
    if (touched.size() <= n) touched.resize(n + 1, 0);
    touched[n] = 1;  // created in this pass
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
