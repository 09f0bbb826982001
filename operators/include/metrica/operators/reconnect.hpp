// The reconnection pass (seed, section 3.1): flips over a work list until
// nothing improves. Seeds are the tets changed since a given epoch whose
// mean ratio is below a threshold (all tets with the defaults). Their edges are tried once each
// for removal (3-2, 4-4, n -> 2n-4, boundary 2-2), in vertex order (after
// compact() that is space order, the seed's buckets for locality), then
// their faces for a 2-3 flip, all under one Criterion.
#pragma once

#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/flips.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/pass_scope.hpp>
#include <metrica/operators/work_list.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <vector>

namespace metrica {

struct ReconnectOptions {
  FlipOptions flips;
  // Tets with mean ratio >= this are not seeds (1: every tet is).
  double seed_below = 1.0;
  // Only tets written since scope.changed_since are seeds (a flip's
  // decision reads only its shell).
  PassScope scope{};
  // Sweeps: the first over the seeds, each later one over the tets the
  // previous sweep wrote; stops early when a sweep changes less than
  // min_change of the tets.
  int max_sweeps = 4;
  double min_change = 1e-3;
  bool face_flips = true;
  // A face is tried for a 2-3 flip only when the worse of its two tets is
  // below this mean ratio (1: every face). Under MinQuality few faces
  // between fair tets flip (docs/benchmarks.md, "Figures behind the
  // code").
  double face_flip_below = 1.0;
};

template <MetricSpace S, Concurrency C, class Criterion, Geometry G = ModelOrFacets>
OperatorStats reconnect(Mesh& mesh, const ReconnectOptions& o = {}, const G& geometry = {}) {
  Stopwatch clock;
  OperatorStats stats;
  const EdgeRemoval<S, Criterion, G> removal{o.flips, geometry};
  const FaceFlip<S, Criterion, G> face_flip{o.flips, o.face_flip_below, geometry};
  std::vector<TetId> seeds;
  MeshArray<EdgeSeed> edges;
  Mesh::Epoch since = o.scope.changed_since;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    const Mesh::Epoch sweep_epoch = mesh.next_epoch();
    seeds = C::template collect<TetId>(mesh.tet_capacity(), [&](std::size_t i, std::vector<TetId>& part) {
      const auto t = static_cast<TetId>(i);
      if (mesh.tet_alive(t) && mesh.changed_since(t, since) &&
          (o.seed_below >= 1.0 || cached_mean_ratio<S>(mesh, t) < o.seed_below))
        part.emplace_back(t);
    });
    // Each edge once per sweep, in vertex order (space order after compact).
    unique_edge_seeds<C>(
        std::span<const TetId>(seeds), [&](TetId t) -> const TetVertices& { return mesh.tet(t); },
        mesh.vertex_capacity(), edges);
    since = sweep_epoch;
    const std::size_t applied_before = stats.applied;
    stats += run_pass<C>(mesh, removal, std::span<const EdgeSeed>(edges.data(), edges.size()));
    if (o.face_flips) stats += run_pass<C>(mesh, face_flip, seeds);
    const std::size_t applied = stats.applied - applied_before;
    if (static_cast<double>(applied) <= o.min_change * static_cast<double>(mesh.num_tets())) break;
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
