// The adaptation pipeline of DESIGN.md ("What one adaptation does"):
//
//   cycle, until little changes or max_cycles:
//     collapse short edges -> refine long edges -> reconnect (flips)
//     -> collapse the short edges refinement made -> smooth poor tets
//   quality phase: reconnect + smooth, quality_passes times; then, while a
//   tet is below repair_below, a repair round around the poor tets
//
// A template over <Space, Precision, Concurrency>; adapt_<space>.cpp
// instantiate the combinations the CLI offers (adapt_dispatch.hpp).
#pragma once

#include <metrica/operators/collapse.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/operators/reconnect.hpp>
#include <metrica/operators/refine_centroids.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/operators/smooth.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <span>
#include <vector>

namespace metrica {

struct CycleReport {
  int cycle = 0;  // 0.. for adaptation cycles; quality passes follow
  bool quality_phase = false;
  bool repair = false;  // a repair round of the quality phase
  std::size_t vertices = 0, tets = 0;
  OperatorStats collapse, refine, reconnect, smooth;
  double conformity = 0;  // share of edges with L in [1/sqrt 2, sqrt 2]
  double min_quality = 0;
  double seconds = 0;     // of this cycle
};

// How new points are made (seed, section 3.2): split the long edges at
// their metric midpoints (Mmg, Omega_h, refine), or insert the centroids of
// the tets with a long edge with the encroachment rules (the seed's).
enum class PointRule { edge, centroid };

struct AdaptOptions {
  int max_cycles = 15;
  PointRule points = PointRule::edge;
  // Stop cycling when a cycle splits and collapses fewer than this share
  // of the vertices.
  double min_change = 0.002;
  // ... or, once the mesh is nearly a unit mesh (at least
  // near_unit_conformity of its edges in range), when a cycle raises that
  // share by less than min_conformity_gain: the last cycles trade splits
  // for collapses and gain little, the quality phase's smoothing gains more
  // per second (0.6M tets of linear: 13.9 s -> 12.9 s, 98.48% -> 98.33%
  // in range, min Q 0.39 -> 0.54). Far from a unit mesh the share can stall or
  // fall while the operators work, so the rule waits.
  double min_conformity_gain = 0.005;
  double near_unit_conformity = 0.9;
  int quality_passes = 4;
  RefineOptions refine;
  CollapseOptions collapse;
  // Flips: one sweep per cycle over the edges and faces of the changed
  // tets below Q 0.7 (measured on linear / polar-1: all tets 4.46 s /
  // 9.61 s, 98.20% / 91.96% in range; below 0.7 3.80 s / 8.83 s, 98.27% /
  // 92.03%; below 0.5 3.65 s / 8.35 s, 97.66% / 91.52%); the quality
  // phase sweeps from the tets below polish_below until little changes.
  //
  // Edge removals skip short edges with large rings (FlipOptions): on a
  // 943k-tet linear adaptation 37.0 s against 38.0 s, 98.51% / 98.47% in
  // range; 28k tets, 7.45 G against 8.42 G instructions.
  // 2-3 flips only across faces with a tet below 0.3: on a 224k-tet run,
  // the faces whose worse tet was in [0.3, 0.6) took 1.12M tries for 3.9k
  // flips; 28k tets 7.27 G against 7.45 G instructions, the UGAWG cases'
  // 5th iterations within 0.2% in range and min Q (0.6: linear / polar-1
  // / polar-2 99.61% / 94.43% / 99.30%, min Q 0.58 / 0.34 / 0.63; 0.3:
  // 99.62% / 94.61% / 99.33%, 0.61 / 0.40 / 0.62).
  ReconnectOptions reconnect{.flips = {.short_edge_ring4 = 0.8, .short_edge_ring5 = 1.0},
                             .seed_below = 0.7,
                             .max_sweeps = 1,
                             .face_flip_below = 0.3};
  double polish_below = 0.8;
  SmoothOptions smooth{.below = 0.3};
  // Smoothing threshold during the quality phase: every vertex (measured:
  // min Q 0.40 -> 0.64 on the UGAWG linear case against 0.4).
  double quality_phase_smooth_below = 1.0;
  // Repair: tets still below repair_below after the quality passes (0.3,
  // the "poor" of the flips and the cycles' smoothing) are held by what
  // flips and smoothing cannot change: a short edge whose collapse was
  // refused when the cycles last tried it, a long ridge edge a split
  // skipped, a surface vertex nearly on a ridge in the metric. A round
  // first collapses edges of any length at the poor tets' vertices where
  // that lifts the worst tet of the ball, then runs the cycle's operators
  // (edge splits whatever the point rule) on the balls of the poor tets'
  // vertices and what those operators change, then one quality pass; at
  // most repair_rounds rounds, and none after two in a
  // row that left the worst tet where it was. One such round can prepare
  // the next (the repair test's fixture on one Speculative thread: 0.255,
  // 0.255, then 0.61), and slow climbs need many (a two-thread run: 0.075,
  // 0.092, 0.181, 0.197 in four). Measured on two-thread adaptations of
  // the parallel tests' case (about 3,200 tets): README, session 15.
  double repair_below = 0.3;
  int repair_rounds = 8;
  // When set, new and moved vertices take this metric (analytic cases).
  const MetricFunction* metric = nullptr;
  // Called after every cycle and quality pass (progress output).
  std::function<void(const CycleReport&)> on_cycle;
};

struct AdaptReport {
  std::vector<CycleReport> cycles;
  OperatorStats collapse, refine, reconnect, smooth;
  double seconds = 0;
};

// The share of edges in [1/sqrt 2, sqrt 2] and, when asked, the smallest
// mean ratio (through the quality cache when `cached`: only while the
// cache is known to hold S's values, as inside adapt).
template <MetricSpace S, class C = Serial>
double conformity(const Mesh& mesh, double* min_quality = nullptr, bool cached = false) {
  // Edges in range and in all, per part of the edge buckets; the minimum
  // in blocks of 64 tets; on C's threads.
  constexpr std::size_t kBlock = 64;
  const std::size_t parts = sweep_parts<C>(mesh.tet_capacity());
  struct alignas(64) Count {
    std::size_t in = 0, all = 0;
  };
  std::vector<Count> counts(parts);
  for_each_mesh_edge_bucket<C>(mesh, parts, [&](std::size_t p, VertexId a, std::span<const VertexId> kept) {
    std::size_t in = 0;
    for (VertexId b : kept) {
      const double l = S::edge_length(mesh, a, b);
      in += kUnitBand.contains(l);
    }
    counts[p].in += in;
    counts[p].all += kept.size();
  });
  std::size_t in = 0, all = 0;
  for (const Count& c : counts) {
    in += c.in;
    all += c.all;
  }
  if (min_quality != nullptr) {
    const std::size_t nt = mesh.tet_capacity();
    const auto mins = C::template collect<double>((nt + kBlock - 1) / kBlock, [&](std::size_t b, std::vector<double>& part) {
      double q = 1.0;
      for (auto t = static_cast<TetId>(b * kBlock); t < std::min(nt, (b + 1) * kBlock); ++t)
        if (mesh.tet_alive(t))
          q = std::min(q, cached ? cached_mean_ratio<S>(mesh, t) : S::mean_ratio(mesh, mesh.tet(t)));
      part.push_back(q);
    });
    *min_quality = mins.empty() ? 1.0 : *std::min_element(mins.begin(), mins.end());
  }
  return all == 0 ? 0.0 : static_cast<double>(in) / static_cast<double>(all);
}

// The tets whose mean ratio (cached, as adapt keeps it) is below `below`.
template <MetricSpace S, Concurrency C>
std::vector<TetId> poor_tets(const Mesh& mesh, double below) {
  constexpr std::size_t kBlock = 256;
  const std::size_t nt = mesh.tet_capacity();
  return C::template collect<TetId>((nt + kBlock - 1) / kBlock, [&](std::size_t b, std::vector<TetId>& part) {
    for (auto t = static_cast<TetId>(b * kBlock); t < std::min(nt, (b + 1) * kBlock); ++t)
      if (mesh.tet_alive(t) && cached_mean_ratio<S>(mesh, t) < below) part.push_back(t);
  });
}

// Touches the tets below `below`, so that a pass limited to the tets
// changed since the current epoch works at their vertices.
template <MetricSpace S, Concurrency C>
void touch_poor_tets(Mesh& mesh, double below) {
  for (TetId t : poor_tets<S, C>(mesh, below)) mesh.touch_tet(t);
}

// Touches the balls of the vertices of the tets below `below`, so that
// passes limited to the tets changed since the current epoch work around
// them.
template <MetricSpace S, Concurrency C>
void touch_around_poor_tets(Mesh& mesh, double below) {
  std::vector<VertexId> vertices;
  for (TetId t : poor_tets<S, C>(mesh, below)) vertices.insert(vertices.end(), mesh.tet(t).begin(), mesh.tet(t).end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  TetList ball;
  for (VertexId v : vertices) {
    vertex_ball(mesh, v, ball);
    for (TetId t : ball) mesh.touch_tet(t);
  }
}

template <MetricSpace S, Precision P, Concurrency C>
AdaptReport adapt(Mesh& mesh, const AdaptOptions& options) {
  Stopwatch total;
  AdaptReport report;
  AdaptOptions o = options;
  mesh.clear_quality_cache();  // the metric or the Space may have changed
  o.refine.metric = o.metric;
  o.smooth.metric = o.metric;
  o.collapse.metric = o.metric;
  auto finish = [&](CycleReport& c, const Stopwatch& clock) {
    mesh.compact(part_runner<C>(mesh.tet_capacity()));
    c.vertices = mesh.num_vertices();
    c.tets = mesh.num_tets();
    c.conformity = conformity<S, C>(mesh, &c.min_quality, true);
    c.seconds = clock.seconds();
    report.collapse += c.collapse;
    report.refine += c.refine;
    report.reconnect += c.reconnect;
    report.smooth += c.smooth;
    report.cycles.push_back(c);
    if (o.on_cycle) o.on_cycle(c);
  };
  // Each pass tries only what changed since the same pass last ran
  // (Mesh epochs; see ReconnectOptions::changed_since): later cycles cost
  // what they change, not the size of the mesh.
  auto run = [&mesh](auto& pass_options, auto&& pass) {
    const Mesh::Epoch start = mesh.next_epoch();
    OperatorStats stats = pass(pass_options);
    pass_options.changed_since = start;
    return stats;
  };
  CollapseOptions& collapse_o = o.collapse;
  ReconnectOptions& flip_o = o.reconnect;
  SmoothOptions& smooth_o = o.smooth;
  ReconnectOptions delaunay_o = o.reconnect;
  // The Delaunay criterion does not follow quality (the face and short-edge
  // filters were measured under MinQuality).
  delaunay_o.face_flip_below = 1.0;
  delaunay_o.flips.short_edge_ring4 = delaunay_o.flips.short_edge_ring5 = 0.0;
  double previous_conformity = 0.0;
  for (int cycle = 0; cycle < o.max_cycles; ++cycle) {
    Stopwatch clock;
    CycleReport c;
    c.cycle = cycle;
    c.collapse = run(collapse_o, [&](auto& x) { return collapse_edges<S, P, C>(mesh, x); });
    c.refine = o.points == PointRule::edge ? refine_edges<S, P, C>(mesh, o.refine)
                                           : refine_centroids<S, P, C>(mesh, o.refine);
    if (o.points == PointRule::centroid) {
      // A centroid leaves its tet's long edge in place; metric Delaunay
      // flips remove it (the seed pairs the rule with them). Sweeping only
      // around the new points was a third faster and lost 2.5 points of
      // conformity (polar-1 87.5% -> 85.0%, linear 96.5% -> 94.9%).
      c.reconnect = run(delaunay_o, [&](auto& x) { return reconnect<S, P, C, MetricDelaunay>(mesh, x); });
    }
    c.reconnect += run(flip_o, [&](auto& x) { return reconnect<S, P, C, MinQuality>(mesh, x); });
    c.collapse += run(collapse_o, [&](auto& x) { return collapse_edges<S, P, C>(mesh, x); });
    c.smooth = run(smooth_o, [&](auto& x) { return smooth_vertices<S, P, C>(mesh, x); });
    const std::size_t changed = c.collapse.applied + c.refine.applied;
    finish(c, clock);
    if (static_cast<double>(changed) < o.min_change * static_cast<double>(mesh.num_vertices())) break;
    if (previous_conformity >= o.near_unit_conformity && c.conformity - previous_conformity < o.min_conformity_gain)
      break;
    previous_conformity = c.conformity;
  }
  // The quality phase: flips from the tets below polish_below, smoothing
  // of every vertex. A pass whose threshold is larger than in the cycles
  // tries everything once (tets the cycles skipped for their quality
  // were never tried), then only what changed.
  if (o.polish_below > flip_o.seed_below) flip_o.changed_since = 0;
  flip_o.seed_below = o.polish_below;
  flip_o.max_sweeps = 4;
  if (o.quality_phase_smooth_below > smooth_o.below) smooth_o.changed_since = 0;
  smooth_o.below = o.quality_phase_smooth_below;
  for (int pass = 0; pass < o.quality_passes; ++pass) {
    Stopwatch clock;
    CycleReport c;
    c.cycle = static_cast<int>(report.cycles.size());
    c.quality_phase = true;
    c.reconnect = run(flip_o, [&](auto& x) { return reconnect<S, P, C, MinQuality>(mesh, x); });
    c.smooth = run(smooth_o, [&](auto& x) { return smooth_vertices<S, P, C>(mesh, x); });
    finish(c, clock);
  }
  int idle_rounds = 0;  // in a row, without a gain in the worst tet
  for (int round = 0; round < o.repair_rounds && idle_rounds < 2; ++round) {
    if (report.cycles.empty()) break;
    const double worst = report.cycles.back().min_quality;
    if (worst >= o.repair_below) break;
    Stopwatch clock;
    CycleReport c;
    c.cycle = static_cast<int>(report.cycles.size());
    c.quality_phase = c.repair = true;
    // First the edges at the poor tets' vertices, of any length, where a
    // collapse lifts the worst tet of its ball (a surface vertex nearly on
    // a ridge in the metric makes a flat tet of unit edges, which neither
    // a short-edge collapse nor smoothing in its plane removed).
    CollapseOptions lift_o = collapse_o;
    lift_o.min_length = std::numeric_limits<double>::infinity();
    lift_o.require_gain = true;
    lift_o.changed_since = mesh.next_epoch();
    touch_poor_tets<S, C>(mesh, o.repair_below);
    c.collapse = collapse_edges<S, P, C>(mesh, lift_o);
    const Mesh::Epoch start = mesh.next_epoch();
    touch_around_poor_tets<S, C>(mesh, o.repair_below);
    collapse_o.changed_since = flip_o.changed_since = smooth_o.changed_since = start;
    RefineOptions refine_o = o.refine;
    refine_o.changed_since = start;
    c.collapse += run(collapse_o, [&](auto& x) { return collapse_edges<S, P, C>(mesh, x); });
    c.refine = refine_edges<S, P, C>(mesh, refine_o);
    c.reconnect = run(flip_o, [&](auto& x) { return reconnect<S, P, C, MinQuality>(mesh, x); });
    c.collapse += run(collapse_o, [&](auto& x) { return collapse_edges<S, P, C>(mesh, x); });
    c.smooth = run(smooth_o, [&](auto& x) { return smooth_vertices<S, P, C>(mesh, x); });
    c.reconnect += run(flip_o, [&](auto& x) { return reconnect<S, P, C, MinQuality>(mesh, x); });
    c.smooth += run(smooth_o, [&](auto& x) { return smooth_vertices<S, P, C>(mesh, x); });
    finish(c, clock);
    idle_rounds = c.min_quality > worst ? 0 : idle_rounds + 1;
  }
  report.seconds = total.seconds();
  return report;
}

}  // namespace metrica
