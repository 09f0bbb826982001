// The reconnection pass (seed, section 3.1): flips over a work list until
// nothing improves. Seeds are the tets changed since a given epoch whose
// mean ratio is below a threshold (all tets with the defaults). Their edges are tried once each
// for removal (3-2, 4-4, n -> 2n-4, boundary 2-2), in vertex order (after
// compact() that is space order, the seed's buckets for locality), then
// their faces for a 2-3 flip, all under one Criterion.
#pragma once

#include <metrica/operators/flips.hpp>
#include <metrica/operators/operator_stats.hpp>
#include <metrica/operators/work_list.hpp>
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
  // A face is tried for a 2-3 flip only when the worse of its two tets is
  // below this mean ratio (1: every face). Under MinQuality few faces
  // between fair tets flip: on a 224k-tet linear run, 2.7M of 4.0M face
  // tries had both tets at Q >= 0.6 and 833 of them flipped; the 2.7M
  // tries were ~1.5 s of a 13 s adaptation.
  double face_flip_below = 1.0;
};

template <MetricSpace S, Precision P, Concurrency C, class Criterion>
OperatorStats reconnect(Mesh& mesh, const ReconnectOptions& o = {}) {
  Stopwatch clock;
  OperatorStats stats;
  std::vector<TetId> seeds;
  // Each edge with a tet that held it when the work list was made (the
  // shell walk starts there when the tet still holds it, else from a's
  // ball).
  MeshArray<EdgeSeed> edges;
  struct Scratch {
    FlipScratch s;
    VertexList cavity;
  };
  std::vector<PerThread<Scratch>> threads(static_cast<std::size_t>(C::threads()));
  auto remove = [&](const EdgeSeed& e, int thread, typename C::Locks& locks) {
    auto& [x, st] = threads[static_cast<std::size_t>(thread)];
    FlipScratch& s = x.s;
    const auto [a, b] = edge_from_key(e.key);
    if (!locks.acquire({a, b})) return Attempt::conflict;
    if (!mesh.vertex_alive(a) || !mesh.vertex_alive(b)) return Attempt::done;
    // Holding a, a tet that shows a and b holds them for good (a writer
    // would hold a), so its peeked vertices are its vertices.
    const TetVertices held = mesh.peek_tet(e.tet);
    if (local_index(held, a) >= 0 && local_index(held, b) >= 0) {
      edge_shell_from(mesh, a, b, e.tet, s.shell);
    } else {
      vertex_ball(mesh, a, s.ball);
      if (!edge_shell(mesh, a, b, s.ball, s.shell)) return Attempt::done;  // gone since
    }
    x.cavity.clear();
    x.cavity.push_back(a);
    x.cavity.push_back(b);
    append_vertices(mesh, s.shell.tets, x.cavity);
    if (!locks.acquire(view(x.cavity))) return Attempt::conflict;
    ++st.tried;
    const FlipResult r = remove_edge<S, P, Criterion>(mesh, a, b, s, o.flips);
    if (r == FlipResult::applied) ++st.applied;
    else if (r == FlipResult::rejected) ++st.rejected;
    return Attempt::done;
  };
  // 2-3 flips across the faces of a seed still there.
  auto flip_faces = [&](TetId t, int thread, typename C::Locks& locks) {
    auto& [x, st] = threads[static_cast<std::size_t>(thread)];
    const TetVertices tv = mesh.peek_tet(t);
    if (tv[0] == kNoId || tv[1] == kNoId || tv[2] == kNoId || tv[3] == kNoId) return Attempt::done;
    if (!locks.acquire(std::span<const VertexId>(tv))) return Attempt::conflict;
    if (mesh.tet(t) != tv) return Attempt::done;  // changed since the list was made
    const bool t_below = o.face_flip_below >= 1.0 || cached_mean_ratio<S>(mesh, t) < o.face_flip_below;
    for (int f = 0; f < 4; ++f) {
      const FaceRef nb = mesh.neighbour(t, f);
      if (!nb.valid()) continue;
      if (!locks.acquire({mesh.tet(nb.tet())[nb.face()]})) return Attempt::conflict;
      if (!t_below && cached_mean_ratio<S>(mesh, nb.tet()) >= o.face_flip_below) continue;
      ++st.tried;
      const FlipResult r = flip23<S, P, Criterion>(mesh, t, f, x.s, o.flips);
      if (r == FlipResult::applied) {
        ++st.applied;
        break;  // t is gone
      }
      if (r == FlipResult::rejected) ++st.rejected;
    }
    return Attempt::done;
  };
  Mesh::Epoch since = o.changed_since;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    const Mesh::Epoch sweep_epoch = mesh.next_epoch();
    seeds = C::template collect<TetId>(mesh.tet_capacity(), [&](std::size_t i, std::vector<TetId>& part) {
      const auto t = static_cast<TetId>(i);
      if (mesh.tet_alive(t) && mesh.changed_since(t, since) &&
          (o.seed_below >= 1.0 || cached_mean_ratio<S>(mesh, t) < o.seed_below))
        part.push_back(t);
    });
    // Each edge once per sweep, in vertex order (space order after compact).
    unique_edge_seeds<C>(std::span<const TetId>(seeds), [&](TetId t) -> const TetVertices& { return mesh.tet(t); },
                      mesh.vertex_capacity(), edges);
    since = sweep_epoch;
    const std::size_t applied_before = stats.applied;
    for (auto& t : threads) t.stats = {};
    // An edge removal of n tets makes 2n - 4 (a 2-3 flip one more), but
    // few tries are applied (1-5%): room for a net 0.05 tets per item, more
    // between rounds when needed (1.0 per item held 400 MB of dead ids at
    // 4.4M tets).
    const PassRoom room{.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 0.05};
    stats.add(C::for_each(mesh, std::span<const EdgeSeed>(edges), room, remove));
    if (o.face_flips) stats.add(C::for_each(mesh, std::span<const TetId>(seeds), room, flip_faces));
    add_thread_counts(stats, threads);
    const std::size_t applied = stats.applied - applied_before;
    if (static_cast<double>(applied) <= o.min_change * static_cast<double>(mesh.num_tets())) break;
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
