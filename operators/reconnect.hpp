// The reconnection pass (seed, section 3.1): flips over a work list until
// nothing improves. Seeds are the tets whose mean ratio is below a
// threshold (all tets with the default 1). Their edges are tried once each
// for removal (3-2, 4-4, n -> 2n-4, boundary 2-2), in vertex order (after
// compact() that is space order, the seed's buckets for locality), then
// their faces for a 2-3 flip, all under one Criterion.
#pragma once

#include <metrica/operators/flips.hpp>
#include <metrica/operators/operator_stats.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <vector>

namespace metrica {

struct ReconnectOptions {
  FlipOptions flips;
  // Tets with mean ratio >= this are not seeds (1: every tet is).
  double seed_below = 1.0;
  // Sweeps over the (recomputed) work list; stops early when a sweep
  // changes less than min_change of the tets.
  int max_sweeps = 4;
  double min_change = 1e-3;
  bool face_flips = true;
};

template <MetricSpace S, Precision P, Concurrency C, class Criterion>
OperatorStats reconnect(Mesh& mesh, const ReconnectOptions& o = {}) {
  Stopwatch clock;
  OperatorStats stats;
  FlipScratch s;
  VertexList cavity;
  typename C::Locks locks;
  std::vector<TetId> seeds;
  auto lock = [&](std::span<const VertexId> vertices) {
    if (locks.acquire(vertices)) return true;
    ++stats.conflicts;
    return false;
  };
  std::vector<std::uint64_t> edges;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    seeds.clear();
    edges.clear();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t) && (o.seed_below >= 1.0 || S::mean_ratio(mesh, mesh.tet(t)) < o.seed_below)) {
        seeds.push_back(t);
        const auto& tv = mesh.tet(t);
        for (const auto& e : kEdgeVertex) edges.push_back(edge_key(tv[e[0]], tv[e[1]]));
      }
    // Each edge once per sweep, in vertex order (space order after compact).
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::size_t applied = 0;
    for (const std::uint64_t key : edges) {
      const auto [a, b] = edge_from_key(key);
      if (!mesh.vertex_alive(a) || !mesh.vertex_alive(b)) continue;
      vertex_ball(mesh, a, s.ball);
      if (!edge_shell(mesh, a, b, s.ball, s.shell)) continue;  // gone since
      cavity.clear();
      cavity.push_back(a);
      cavity.push_back(b);
      for (TetId u : s.shell.tets)
        for (VertexId v : mesh.tet(u))
          if (std::find(cavity.begin(), cavity.end(), v) == cavity.end()) cavity.push_back(v);
      if (!lock(view(cavity))) continue;
      ++stats.tried;
      const FlipResult r = remove_edge<S, P, Criterion>(mesh, a, b, s, o.flips);
      locks.release();
      if (r == FlipResult::applied) ++applied;
      else if (r == FlipResult::rejected) ++stats.rejected;
    }
    // 2-3 flips across the faces of the seeds still there.
    for (TetId t : seeds) {
      if (!o.face_flips || !mesh.tet_alive(t)) continue;
      for (int f = 0; f < 4; ++f) {
        const FaceRef nb = mesh.neighbour(t, f);
        if (!nb.valid()) continue;
        const TetVertices tv = mesh.tet(t);
        const std::array<VertexId, 5> five{tv[0], tv[1], tv[2], tv[3], mesh.tet(nb.tet())[nb.face()]};
        if (!lock(five)) continue;
        ++stats.tried;
        const FlipResult r = flip23<S, P, Criterion>(mesh, t, f, s);
        locks.release();
        if (r == FlipResult::applied) {
          ++applied;
          break;  // t is gone
        }
        if (r == FlipResult::rejected) ++stats.rejected;
      }
    }
    stats.applied += applied;
    if (static_cast<double>(applied) <= o.min_change * static_cast<double>(mesh.num_tets())) break;
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
