// The standard adaptation, as a pipeline of stages on an Adapter:
//
//   cycle, until little changes or max_cycles:
//     collapse short edges -> refine long edges -> reconnect (flips)
//     -> collapse the short edges refinement made -> smooth poor tets
//   quality phase: reconnect + smooth, quality_passes times; then, while a
//   tet is below repair_below, a repair round around the poor tets
//
// AdaptOptions holds the standard pipeline's settings; Pipeline is any
// list of stages with its stopping rules, run by run_pipeline.
#pragma once

#include <metrica/geometry/cad_geometry.hpp>
#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/pipeline/adapter.hpp>
#include <metrica/pipeline/standard_stages.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace metrica {

// How new points are made (seed, section 3.2): split the long edges at
// their metric midpoints (Mmg, Omega_h, refine), or insert the centroids of
// the tets with a long edge with the encroachment rules (the seed's).
enum class PointRule { edge, centroid };

// When a pipeline stops cycling, how many quality passes it runs and when
// it repairs: the rules of run_pipeline, shared by Pipeline and
// AdaptOptions (the standard pipeline's defaults, stated here once). The
// figures behind each default are in docs/benchmarks.md ("Why the
// defaults").
struct PipelineRules {
  int max_cycles = 15;
  // Stop cycling when a cycle creates and removes fewer vertices than this
  // share of the vertices (Mesh::vertex_changes: whatever its stages are
  // called and do) ...
  double min_change = 0.002;
  // ... or, once at least near_unit_conformity of the edges are in the
  // unit band, when a cycle raises that share by less than
  // min_conformity_gain: the last cycles trade splits for collapses, and
  // the quality phase gains more per second (a cycle that adds under one
  // point costs as much as a quality pass that adds more). Far from a
  // unit mesh the share can stall while the operators work, so the rule
  // waits.
  double min_conformity_gain = 0.01;
  double near_unit_conformity = 0.9;
  int quality_passes = 4;
  // Repair rounds while the worst tet is below repair_below, at most
  // repair_rounds, none after two in a row that leave the worst tet where
  // it was (one round can prepare the next, and slow climbs need several).
  double repair_below = 0.3;
  int repair_rounds = 8;
};

// The settings of the standard pipeline: its rules, and what its stages
// do. Every default of the library, the command (metrica adapt's option
// defaults are read from AdaptOptions{}) and the docs is stated here or in
// the operations' options it holds.
struct AdaptOptions : PipelineRules {
  PointRule points = PointRule::edge;
  RefineOptions refine;
  CollapseOptions collapse;
  // Flips: one sweep per cycle from the changed tets below Q 0.7 (all tets
  // cost 15% more time for no gain in range); edge removals skip short
  // edges with large rings and shells of 5 or 6 ring vertices whose worst
  // tet is at 0.7 or above (0.6 from 7 on), and 2-3 flips need a tet below
  // 0.3 across the face (all rarely flip). The quality phase sweeps from
  // the tets below polish_below, polish_sweeps times a pass at most.
  ReconnectOptions reconnect{
      .flips = {.short_edge_ring4 = 0.8, .short_edge_ring5 = 1.0, .good_shell = {1, 1, 1, 1, 1, 0.7, 0.7, 0.6}},
      .seed_below = 0.7,
      .max_sweeps = 1,
      .face_flip_below = 0.3};
  double polish_below = 0.75;
  // Two sweeps a pass: the later sweeps of a pass flip what the next
  // pass's first sweep would.
  int polish_sweeps = 2;
  // Smoothing in the cycles: the vertices of tets below 0.5 (each move
  // refused where it leaves more of its edges off the unit band). Against
  // 0.3: more edges in range where a field given on a coarse mesh varies
  // much over a move, and fewer vertices for the complexity; 0.7 and up
  // gain more in range and take the tanh3 loop's error beyond +2% at equal
  // complexity (docs/benchmarks.md).
  SmoothOptions smooth{.below = 0.5};
  // Smoothing in the quality phase: every vertex (UGAWG linear: min Q 0.64
  // against 0.40 with 0.4).
  double quality_phase_smooth_below = 1.0;
  // Repair (PipelineRules::repair_below, repair_rounds): tets still below
  // repair_below after the quality passes are held by what flips and
  // smoothing cannot change (a short edge whose collapse was refused, a
  // long ridge edge a split skipped, a surface vertex nearly on a ridge in
  // the metric). A round first collapses edges of any length at the poor
  // tets' vertices where that lifts the worst tet of the ball, then runs
  // the cycle's operators around the poor tets, then one quality pass.
  // On a model, the closing stage's rounds (projection, then flips and
  // smoothing around the vertices still off the model); the last round
  // collapses those it leaves onto a boundary neighbour.
  int closing_rounds = 4;
  // Off a model, the boundary collapses of one adaptation may change the
  // domain's volume by at most this share of it (volume_budget.hpp).
  double volume_budget = kDefaultVolumeBudget;
};

// What an adaptation works with besides its settings (AdaptOptions holds
// settings only).
struct AdaptInputs {
  // When set, new and moved vertices take this metric (analytic cases).
  const MetricFunction* metric = nullptr;
  // Else, when set, they take this background's (the user's field on the
  // mesh it was given on: a metric from a file or arrays); else the Space
  // interpolates the vertices' metrics.
  const BackgroundMetric* background = nullptr;
  MetricSource source() const { return metric != nullptr && *metric ? MetricSource(metric) : background; }
  // When set, boundary vertices are placed on this model (the Geometry
  // made from it: ModelOrFacets, adapt_by_name's, or CadGeometry); the
  // mesh must be associated with it (geometry/association.hpp).
  const CadModel* model = nullptr;
  // Called after every cycle, pass and round (progress output).
  std::function<void(const CycleReport&)> on_cycle;
};

// The Geometry policy object of `inputs`: G{inputs.model} when G is made
// from a model (CadGeometry, ModelOrFacets), else G{}.
template <Geometry G>
G geometry_of(const AdaptInputs& inputs) {
  if constexpr (requires { G{inputs.model}; })
    return G{inputs.model};
  else
    return G{};
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

// A pipeline: the stages of one adaptation cycle, of one pass of the
// quality phase and of one repair round, and when to stop.
template <class A>
struct Pipeline : PipelineRules {
  // Run once, at the start of the first cycle (e.g. the input's vertices
  // off the model onto it).
  Stages<A> opening;
  Stages<A> cycle;
  // At the start of the quality phase (e.g. forget the epochs of passes
  // whose thresholds grow), then its passes.
  std::function<void(A&)> before_polish;
  Stages<A> polish;
  Stages<A> repair;
  // Run once at the end (e.g. the last vertices onto the model).
  Stages<A> closing;
  // Set by standard_pipeline: whether its stages are those on a model or
  // off one. run_pipeline refuses an adapter whose geometry says the other.
  std::optional<bool> for_model;
};

// One round of a pipeline: its stages, then the adapter closes it (counts,
// conformity unless `measure_conformity` is false, worst tet, report,
// progress). `number` is its index in the report; quality-phase rounds
// follow the cycles.
enum class RoundKind { cycle, quality_pass, repair, closing };
template <class A>
const CycleReport& run_round(A& a, const Stages<A>& stages, RoundKind kind, int number, const Stages<A>& first = {},
                             bool measure_conformity = true) {
  Stopwatch clock;
  CycleReport c;
  c.cycle = number;
  c.quality_phase = kind != RoundKind::cycle;
  c.repair = kind == RoundKind::repair;
  run_stages(a, first, c);
  run_stages(a, stages, c);
  a.finish(c, clock, measure_conformity);
  return a.report().cycles.back();
}

// Runs a pipeline: cycles, the quality phase, repair rounds, the closing.
template <class A>
const AdaptReport& run_pipeline(A& a, const Pipeline<A>& p) {
  if (p.for_model && *p.for_model != a.geometry().on_model())
    throw std::invalid_argument(
        fmt::format("run_pipeline: a standard pipeline built for an adaptation {} a model, on an adapter {} one "
                    "(standard_pipeline's on_model: the adapter's geometry().on_model())",
                    *p.for_model ? "on" : "off", *p.for_model ? "off" : "on"));
  Stopwatch total;
  const auto next = [&a] { return static_cast<int>(a.report().cycles.size()); };
  double previous_conformity = 0.0;
  for (int cycle = 0; cycle < p.max_cycles; ++cycle) {
    const std::uint64_t changes_before = a.mesh().vertex_changes();
    const double conformity =
        run_round(a, p.cycle, RoundKind::cycle, cycle, cycle == 0 ? p.opening : Stages<A>{}).conformity;
    const std::uint64_t changed = a.mesh().vertex_changes() - changes_before;
    if (static_cast<double>(changed) < p.min_change * static_cast<double>(a.mesh().num_vertices())) break;
    if (previous_conformity >= p.near_unit_conformity && conformity - previous_conformity < p.min_conformity_gain)
      break;
    previous_conformity = conformity;
  }
  if (p.before_polish) p.before_polish(a);
  // The quality passes' share in range decides nothing (the cycles' stops
  // are behind; the repair rounds start from the worst tet): the last
  // pass's only is measured.
  for (int pass = 0; pass < p.quality_passes; ++pass)
    run_round(a, p.polish, RoundKind::quality_pass, next(), {}, pass + 1 == p.quality_passes);
  int idle_rounds = 0;  // in a row, without a gain in the worst tet
  for (int round = 0; round < p.repair_rounds && idle_rounds < 2 && !p.repair.empty(); ++round) {
    if (a.report().cycles.empty()) break;
    const double worst = a.report().cycles.back().min_quality;
    if (worst >= p.repair_below) break;
    const double after = run_round(a, p.repair, RoundKind::repair, next()).min_quality;
    idle_rounds = after > worst ? 0 : idle_rounds + 1;
  }
  if (!p.closing.empty()) run_round(a, p.closing, RoundKind::closing, next());
  a.report().seconds = total.seconds();
  return a.report();
}

// The standard pipeline of AdaptOptions:
//
//   opening   on a model: the input's vertices off it, onto it;
//   cycle     collapse, split (or centroids + metric Delaunay flips),
//             quality flips, the internal surfaces' swaps and 2-2 flips,
//             collapse, smoothing of the poor tets;
//   polish    quality flips from the tets below polish_below, the
//             internal surfaces' swaps and flips, smoothing of every vertex;
//   repair    collapses that lift the poor tets, then the cycle's
//             operators on the balls of the poor tets' vertices, and one
//             more flip and smoothing pass;
//   closing   on a model: the vertices left off it, after flips and
//             smoothing around them.
// On a model every cycle, pass and round also projects onto it the
// vertices whose placement had to backtrack, and cycles and passes flip
// boundary edges whose facets then follow the model better (swap).
//
// `on_model`: the stages on a model or off one. By default the Geometry
// type's when the type says (NoGeometry, CadGeometry), else off a model:
// under ModelOrFacets, pass the adapter's geometry().on_model().
template <Geometry G>
constexpr bool on_model_of_type() {
  if constexpr (requires { std::bool_constant<G::on_model()>{}; })
    return G::on_model();
  else
    return false;
}
template <class A, Precision P = Precisions::at<0>>
Pipeline<A> standard_pipeline(const AdaptOptions& o, bool on_model = on_model_of_type<typename A::Geometry>()) {
  using S = typename A::Space;
  using C = typename A::Concurrency;
  Pipeline<A> p;
  static_cast<PipelineRules&>(p) = o;
  const CollapseOptions collapse = o.collapse;
  const RefineOptions refine = o.refine;
  const ReconnectOptions flips = o.reconnect;
  // The Delaunay criterion does not follow quality (the face and short-edge
  // filters were tuned under MinQuality).
  ReconnectOptions delaunay = o.reconnect;
  delaunay.face_flip_below = 1.0;
  delaunay.flips.short_edge_ring4 = delaunay.flips.short_edge_ring5 = 0.0;
  const SmoothOptions smooth = o.smooth;
  ReconnectOptions polish_flips = o.reconnect;
  polish_flips.seed_below = o.polish_below;
  polish_flips.max_sweeps = o.polish_sweeps;
  SmoothOptions polish_smooth = o.smooth;
  polish_smooth.below = o.quality_phase_smooth_below;

  p.for_model = on_model;
  // The input's boundary vertices off the model (association reports
  // them) onto it before anything is decided around them.
  if (on_model) p.opening.push_back({"project", [](A& a) { return a.project(); }});
  p.cycle.push_back({"collapse", [=](A& a) { return a.collapse(collapse); }});
  if (o.points == PointRule::edge) {
    p.cycle.push_back({"split", [=](A& a) { return a.split(refine); }});
    // On a model, an internal surface's split whose model point an inner
    // vertex stands in front of waits; that vertex goes, for the next pass.
    if (on_model) p.cycle.push_back({"clear", [=](A& a) { return a.clear_way(refine); }});
  } else {
    p.cycle.push_back({"centroids", [=](A& a) { return a.insert_centroids(refine); }});
    // A centroid leaves its tet's long edge in place; metric Delaunay flips
    // remove it (the seed pairs the rule with them).
    p.cycle.push_back({"delaunay", [=](A& a) { return a.template flips<MetricDelaunay<P>>(delaunay); }});
  }
  p.cycle.push_back({"flip", [=](A& a) { return a.template flips<MinQuality>(flips); }});
  // On a model: the vertices a split left off it (their tets would have
  // inverted) try again after the reconnection around them.
  if (on_model) p.cycle.push_back({"project", [](A& a) { return a.project(); }});
  // The 2-2 flips toward the model (on one) and of internal surfaces.
  const auto swap = [on_model](A& a) { return on_model ? a.swap() : a.swap_interfaces(); };
  p.cycle.push_back({"swap", swap});
  p.cycle.push_back({"collapse", [=](A& a) { return a.collapse(collapse); }});
  p.cycle.push_back({"smooth", [=](A& a) { return a.smooth(smooth); }});

  // A quality pass whose threshold is larger than in the cycles tries
  // everything once (tets the cycles skipped for their quality were never
  // tried), then only what changed.
  p.before_polish = [=](A& a) {
    if (o.polish_below > flips.seed_below) a.forget("flip");
    if (o.quality_phase_smooth_below > smooth.below) a.forget("smooth");
  };
  p.polish.push_back({"flip", [=](A& a) { return a.template flips<MinQuality>(polish_flips); }});
  if (on_model) p.polish.push_back({"project", [](A& a) { return a.project(); }});
  p.polish.push_back({"swap", swap});
  p.polish.push_back({"smooth", [=](A& a) { return a.smooth(polish_smooth); }});

  // Repair: first the edges at the poor tets' vertices, of any length,
  // where a collapse lifts the worst tet of its ball (a surface vertex
  // nearly on a ridge in the metric makes a flat tet of unit edges, which
  // neither a short-edge collapse nor smoothing in its plane removes);
  // then every incremental pass restarts from the balls of the poor tets'
  // vertices.
  const double below = o.repair_below;
  p.repair.push_back({"lift", [=](A& a) {
                        CollapseOptions lift = collapse;
                        lift.min_length = std::numeric_limits<double>::infinity();
                        lift.require_gain = true;
                        a.mark("lift");
                        touch_poor_tets<S, C>(a.mesh(), below);
                        const OperatorStats stats = a.collapse(lift);
                        a.restart_all(a.mark("repair"));
                        touch_around_poor_tets<S, C>(a.mesh(), below);
                        return stats;
                      }});
  p.repair.push_back({"collapse", [=](A& a) { return a.collapse(collapse); }});
  p.repair.push_back({"split", [=](A& a) {
                        RefineOptions r = refine;
                        r.scope.changed_since = a.since("repair");
                        return a.split(r);
                      }});
  // Splits on an internal surface can fold it over a sliver again.
  p.repair.push_back({"swap", [](A& a) { return a.swap_interfaces(); }});
  p.repair.push_back({"flip", [=](A& a) { return a.template flips<MinQuality>(polish_flips); }});
  p.repair.push_back({"collapse", [=](A& a) { return a.collapse(collapse); }});
  p.repair.push_back({"smooth", [=](A& a) { return a.smooth(polish_smooth); }});
  p.repair.push_back({"flip", [=](A& a) { return a.template flips<MinQuality>(polish_flips); }});
  if (on_model) p.repair.push_back({"project", [](A& a) { return a.project(); }});
  p.repair.push_back({"smooth", [=](A& a) { return a.smooth(polish_smooth); }});
  // On a model, the vertices still off it (their ball would invert) go
  // onto it after flips and smoothing around them, a few times; flips and
  // smoothing follow each projection (it moves vertices for the model,
  // not for quality). Those the last round leaves are collapsed onto a
  // boundary neighbour.
  if (on_model)
    p.closing.push_back({"project", [=, rounds = o.closing_rounds](A& a) {
                           OperatorStats stats;
                           ReconnectOptions around = polish_flips;
                           around.seed_below = 1.0;
                           for (int round = 1; round <= rounds; ++round) {
                             stats += a.project();
                             const auto off =
                                 vertices_off_model<C>(a.mesh(), a.geometry(), ProjectionOptions{}.tolerance);
                             TetList ball;
                             for (VertexId v : off) {
                               vertex_ball(a.mesh(), v, ball);
                               for (TetId t : ball) a.mesh().touch_tet(t);
                             }
                             if (round == rounds && !off.empty())  // the last resort
                               stats += collapse_off_model<S>(a.mesh(), off, a.geometry());
                             // The flips and smoothing of the quality phase, going on from their epochs.
                             a.template flips<MinQuality>(around, "flip");
                             a.smooth(polish_smooth, "smooth");
                             if (off.empty()) break;
                           }
                           return stats;
                         }});
  return p;
}

// The standard adaptation under <S, P, C, G> (P: the metric-Delaunay
// criterion's precision), with the Geometry object given, or made from
// inputs.model (geometry_of).
template <MetricSpace S, Precision P, Concurrency C, Geometry G>
AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, const AdaptInputs& inputs, const G& geometry) {
  Adapter<S, C, G> a(mesh, inputs.source(), geometry);
  a.set_volume_budget(options.volume_budget);
  a.on_cycle = inputs.on_cycle;
  return run_pipeline(a, standard_pipeline<Adapter<S, C, G>, P>(options, geometry.on_model()));
}
template <MetricSpace S, Precision P, Concurrency C, Geometry G = ModelOrFacets>
AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, const AdaptInputs& inputs = {}) {
  return adapt<S, P, C, G>(mesh, options, inputs, geometry_of<G>(inputs));
}

// Compiled in the library (standard_stages.hpp), for the triples and
// precisions pipeline/CMakeLists.txt read from the lists.
static_assert(Spaces::size == METRICA_LISTED_SPACES && Precisions::size == METRICA_LISTED_PRECISIONS &&
                  Concurrencies::size == METRICA_LISTED_CONCURRENCIES && Geometries::size == METRICA_LISTED_GEOMETRIES,
              "the policy lists as pipeline/CMakeLists.txt read them from their headers");
METRICA_FOR_EACH_COMPILED_TRIPLE(METRICA_STANDARD_STAGES_AT, extern)

}  // namespace metrica
