// The reconnection pass (seed, section 3.1): flips over a work list until
// nothing improves. Seeds are the tets changed since a given epoch whose
// mean ratio is below a threshold (all tets with the defaults). Their edges are tried once each
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
  // Only tets written since this epoch are seeds (Mesh::next_epoch; 0:
  // all). A flip's decision reads only its shell, so an edge none of whose
  // tets changed since it was last tried would be refused again.
  Mesh::Epoch changed_since = 0;
  // Sweeps: the first over the seeds, each later one over the tets the
  // previous sweep wrote; stops early when a sweep changes less than
  // min_change of the tets.
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
  // An edge and a tet that held it when the work list was made (the shell
  // walk starts there when the tet still holds it, else from a's ball).
  struct EdgeSeed {
    std::uint64_t key;
    TetId tet;
  };
  std::vector<EdgeSeed> edges;
  Mesh::Epoch since = o.changed_since;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    const Mesh::Epoch sweep_epoch = mesh.next_epoch();
    seeds.clear();
    edges.clear();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t) && mesh.changed_since(t, since) &&
          (o.seed_below >= 1.0 || cached_mean_ratio<S>(mesh, t) < o.seed_below)) {
        seeds.push_back(t);
        const auto& tv = mesh.tet(t);
        for (const auto& e : kEdgeVertex) edges.push_back({edge_key(tv[e[0]], tv[e[1]]), t});
      }
    since = sweep_epoch;
    // Each edge once per sweep, in vertex order (space order after compact).
    std::sort(edges.begin(), edges.end(), [](const EdgeSeed& x, const EdgeSeed& y) { return x.key < y.key; });
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](const EdgeSeed& x, const EdgeSeed& y) { return x.key == y.key; }),
                edges.end());
    std::size_t applied = 0;
    for (const EdgeSeed& e : edges) {
      const auto [a, b] = edge_from_key(e.key);
      if (!mesh.vertex_alive(a) || !mesh.vertex_alive(b)) continue;
      const TetVertices& held = mesh.tet(e.tet);
      if (mesh.tet_alive(e.tet) && local_index(held, a) >= 0 && local_index(held, b) >= 0) {
        edge_shell_from(mesh, a, b, e.tet, s.shell);
      } else {
        vertex_ball(mesh, a, s.ball);
        if (!edge_shell(mesh, a, b, s.ball, s.shell)) continue;  // gone since
      }
      cavity.clear();
      cavity.push_back(a);
      cavity.push_back(b);
      append_vertices(mesh, s.shell.tets, cavity);
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
        const FlipResult r = flip23<S, P, Criterion>(mesh, t, f, s, o.flips);
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
