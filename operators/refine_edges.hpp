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
  // Only edges with an end whose ball changed since this epoch are split
  // (0: all): the quality phase's repair works near its poor tets only.
  Mesh::Epoch changed_since = 0;
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
  const auto todo = edges_beyond<S, C>(mesh, o.max_length, EdgeOrder::longest_first, o.changed_since);
  // Vertices stamped with this epoch or later were created by this pass.
  const Mesh::Epoch pass_epoch = mesh.next_epoch();
  struct Scratch {
    TetList ball;
    Shell shell;
    VertexList cavity;
  };
  std::vector<PerThread<Scratch>> threads(static_cast<std::size_t>(C::threads()));
  auto work = [&](const EdgeCandidate& c, int thread, typename C::Locks& locks) {
    auto& [x, st] = threads[static_cast<std::size_t>(thread)];
    if (!locks.acquire({c.a, c.b})) return Attempt::conflict;
    if (!mesh.vertex_alive(c.a) || !mesh.vertex_alive(c.b)) return Attempt::done;
    vertex_ball(mesh, c.a, x.ball);
    if (!edge_shell(mesh, c.a, c.b, x.ball, x.shell)) return Attempt::done;  // edge gone
    x.cavity.clear();
    append_vertices(mesh, x.shell.tets, x.cavity);
    if (!locks.acquire(view(x.cavity))) return Attempt::conflict;
    ++st.tried;
    const Eigen::Vector3d e = mesh.point(c.b) - mesh.point(c.a);
    const auto& ma = S::vertex_metric(mesh, c.a);
    const auto& mb = S::vertex_metric(mesh, c.b);
    const double t = metric_midpoint(std::sqrt(metric_norm2(ma, e)), std::sqrt(metric_norm2(mb, e)));
    const Point p = mesh.point(c.a) + t * e;
    for (VertexId v : x.cavity) {
      if (mesh.vertex_stamp(v) < pass_epoch) continue;
      const auto& mv = S::vertex_metric(mesh, v);
      if (std::sqrt(metric_norm2(mv, p - mesh.point(v))) < o.min_new_distance) {
        ++st.deferred;  // too close to a point of this pass: next pass
        return Attempt::done;
      }
    }
    if (!split_is_valid<P>(mesh, x.shell, c.a, c.b, p)) {
      ++st.rejected;
      return Attempt::done;
    }
    const std::array<VertexId, 2> ends{c.a, c.b};
    const std::array<double, 2> w{1.0 - t, t};
    const VertexMetric m = new_vertex_metric<S>(mesh, o.metric, ends, w, p);
    split_edge(mesh, x.shell, c.a, c.b, p, m);
    ++st.applied;
    return Attempt::done;
  };
  // A split of a shell of n tets (5 on average) makes n new ones; the
  // proximity filter defers about half of the candidates. More comes
  // between rounds when needed.
  stats.add(C::for_each(mesh, std::span<const EdgeCandidate>(todo),
                        PassRoom{.vertices_per_item = 0.6, .tets_per_item = 3.5}, work));
  add_thread_counts(stats, threads);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
