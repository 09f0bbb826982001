#include <metrica/allocator.hpp>
#include <metrica/distributed/adapt_part.hpp>
#include <metrica/distributed/distributed_adapt.hpp>
#include <metrica/distributed/migrate.hpp>
#include <metrica/distributed/partition.hpp>
#include <metrica/distributed/pinches.hpp>
#include <metrica/distributed/read_part.hpp>
#include <metrica/distributed/write_part.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace metrica::distributed {

namespace {

double det(const Sym6& m) {  // xx xy yy xz yz zz
  return m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) + m[3] * (m[1] * m[4] - m[2] * m[3]);
}

// What each tet will weigh once adapted: its metric volume (the tet's
// volume times the mean sqrt det M of its vertices) in output tets,
// scaled to PT-Scotch's integers.
// About 10 output tets per unit of metric volume (the command's estimate
// of a run's size).
constexpr double kTetsPerMetricVolume = 10;

// Parts worth cutting: no more than the ranks, at least one per
// kMaxPartTets predicted output tets, and none smaller than kMinPartTets
// input tets. A small input cut into many parts has coarse faces between
// them where the metric asks for far smaller tets, and the tets the
// adaptation must leave against those kept faces are very poor: its first
// round then runs on fewer ranks.
constexpr double kMinPartTets = 10'000, kMaxPartTets = 10'000'000;
int parts_for(int ranks, double tets, double predicted) {
  const double by_input = std::floor(tets / kMinPartTets), by_output = std::ceil(predicted / kMaxPartTets);
  return int(std::clamp(std::max(by_input, by_output), 1.0, double(ranks)));
}

std::vector<std::int32_t> predicted_tets(const Comm& comm, const Part& part, const MetricFunction* exact,
                                         double& predicted_total) {
  std::vector<double> root(part.vertex_ids.size());
  for (std::size_t v = 0; v < root.size(); ++v)
    root[v] = std::sqrt(std::max(0.0, det(exact ? (*exact)(part.points[v]) : part.metrics[v])));
  std::vector<double> predicted(part.tets.size());
  double sum = 0;
  for (std::size_t t = 0; t < part.tets.size(); ++t) {
    const auto& v = part.tets[t];
    const Point &a = part.points[v[0]], &b = part.points[v[1]], &c = part.points[v[2]], &d = part.points[v[3]];
    const double volume = std::abs((b - a).dot((c - a).cross(d - a))) / 6.0;
    predicted[t] = volume * (root[v[0]] + root[v[1]] + root[v[2]] + root[v[3]]) / 4.0;
    sum += predicted[t];
  }
  const double total = comm.sum(sum), count = double(comm.sum(std::int64_t(part.tets.size())));
  predicted_total = kTetsPerMetricVolume * total;
  const double mean = total / std::max(1.0, count);
  const double scale = mean > 0 ? std::min(100.0 / mean, double(1 << 30) / total) : 1.0;
  std::vector<std::int32_t> w(part.tets.size());
  for (std::size_t t = 0; t < w.size(); ++t) w[t] = std::int32_t(std::max(1.0, std::round(predicted[t] * scale)));
  return w;
}

// The output's size (all ranks') as the single process predicts it: an
// analytic metric sampled inside the tets, a metric file by the vertex
// formula. `tets`: the input's tets on all ranks.
double predicted_output(const Comm& comm, const Part& part, const MetricFunction* exact, std::int64_t tets) {
  double predicted = 0;
  if (!exact) {
    predicted_tets(comm, part, exact, predicted);
    return predicted;
  }
  const int order = sample_order(double(tets));
  double c = 0;
  for (const auto& t : part.tets) {
    const auto p = [&](int k) { return part.points[t[std::size_t(k)]]; };
    c += sampled_tet_complexity(p(0), p(1), p(2), p(3), *exact, order);
  }
  return kTetsPerMetricVolume * comm.sum(c);
}

// The volume of the part's tets.
double part_volume(const Part& part) {
  double sum = 0;
  for (const auto& t : part.tets) {
    const Point &a = part.points[t[0]], &b = part.points[t[1]], &c = part.points[t[2]], &d = part.points[t[3]];
    sum += (b - a).dot((c - a).cross(d - a)) / 6.0;
  }
  return sum;
}

// How far from what a round left unfinished the next one adapts (edge steps).
constexpr int kFocusLayers = 6;
// Rounds after which the worst adapted tet alone may end an adaptation:
// the first keeps the input's faces between parts, the second cut crosses
// them somewhere in most meshes (two cuts of one domain meet), the third
// adapts there. A second round that held none of what the first left
// unfinished (its cut passed beside it) may end it too.
constexpr int kFewestRounds = 3;

// How many of `before` (sorted) are in `held` (sorted), on all ranks.
std::int64_t held_again(const Comm& comm, const std::vector<GlobalId>& before, const std::vector<GlobalId>& held) {
  std::int64_t n = 0;
  for (GlobalId g : held) n += std::binary_search(before.begin(), before.end(), g);
  return comm.sum(n);
}

// The unfinished vertices (sorted, once each) with those a rank across
// found on the faces this part shares with it: the tets on both sides of
// such a face are in the next round's focus.
std::vector<GlobalId> unfinished_on_both_sides(const Comm& comm, const Part& part, std::vector<GlobalId> mine) {
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  std::vector<std::vector<GlobalId>> out(std::size_t(comm.size()));
  for (std::size_t f = 0; f < part.shared_faces.size(); ++f)
    for (GlobalId g : part.shared_faces[f])
      if (std::binary_search(mine.begin(), mine.end(), g)) out[std::size_t(part.shared_with[f])].push_back(g);
  for (auto& o : out) {
    std::sort(o.begin(), o.end());
    o.erase(std::unique(o.begin(), o.end()), o.end());
  }
  const auto got = comm.exchange(out);
  mine.insert(mine.end(), got.begin(), got.end());
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  return mine;
}

// Whether a part has one of `vertices` (sorted) on a face it shares with
// another, on any rank.
bool on_faces_between_parts(const Comm& comm, const Part& part, const std::vector<GlobalId>& vertices) {
  std::int64_t found = 0;
  for (const auto& f : part.shared_faces)
    for (GlobalId g : f) found += std::binary_search(vertices.begin(), vertices.end(), g);
  return comm.sum(found) > 0;
}

// The most tets a part may hold, against the mean, for a round to run
// without a new cut.
constexpr double kMostWithoutCut = 1.05;

// The weight of the graph edges around what the last round left
// unfinished when the mesh is cut in two (PartitionWeights::heavy else).
// Two parts share one surface, which a new cut can pass beside (one part
// holds it all); where a cut crosses it the next round leaves its poorest
// tets (4.3M tets on 2 ranks at 100: one at 0.005, four rounds; at 1000
// three). More parts' faces meet along lines that any cut crosses, and
// there the larger weight only made rounds poorer (docs/distributed.md).
constexpr std::int32_t kAvoidBetweenTwo = 1000;

// Cuts the mesh into `parts` and moves the tets there; the seconds the
// cut took.
double move_to_parts(const Comm& comm, Part& part, const PartitionWeights& weights, int parts) {
  Stopwatch clock;
  TetNeighbours nb = neighbours(comm, part);
  const auto dest = partition(comm, part, nb, weights, parts);
  const double cut_seconds = clock.seconds();
  part = migrate(comm, std::move(part), std::move(nb), dest);
  // The move's freed buffers back to the kernel: kept, they stood under
  // the next part's mesh (57 MiB of 143 at 4.3M tets on 4 ranks).
  release_freed_memory();
  return cut_seconds;
}

// Each boundary vertex on its entity of `model` (the association of the
// single process: the input's parameters where they give the vertex's
// point, else by projection, from the surface ids around it).
// `report` counts the vertices this rank associates.
AssociateVertex associate_on(const CadModel& model, AssociationReport& report) {
  return [&model, &report, tolerance = 1e-3 * model.size()](GlobalId v, const Point& p, std::span<FanSide> fan,
                                                            const VertexRecords& file) {
    std::vector<int> surfaces;
    for (const auto& side : fan)
      if (std::find(surfaces.begin(), surfaces.end(), side.surface) == surfaces.end()) {
        if (!model.has(2, side.surface)) throw InputError(unknown_surfaces_message({side.surface}, model));
        surfaces.push_back(side.surface);
      }
    const VertexAssociation a = associate_vertex(model, p, surfaces, vertex_class_of_fan(fan), file, tolerance);
    if (!(a.distance <= tolerance)) throw InputError(off_model_message(VertexId(v), p, a, model, tolerance));
    report.add(a);
    return a.param;
  };
}

struct Spread {
  std::int64_t total, low, high;
};
Spread spread(const Comm& comm, std::int64_t local) { return {comm.sum(local), -comm.max(-local), comm.max(local)}; }

// The input as the ranks hold it once read: each rank's slice, the model
// every rank opened, what the file held.
struct Input {
  std::unique_ptr<CadModel> model;
  Part part;
  ReadCounts counts;
  std::int32_t max_ref = 0;  // the largest surface id, over all ranks
};

Input read_input(const Comm& comm, const DistributedAdapt& run, bool talk, const Stopwatch& clock) {
  Input in;
  // Every rank opens the model, rank 0 first: an error is said once.
  if (!run.geometry.empty())
    for (const bool first : {true, false})
      comm.step([&] {
        if ((comm.rank() == 0) == first) in.model = std::make_unique<CadModel>(run.geometry);
      });
  AssociationReport associated;
  in.part = read_part(comm, run.input, run.metric, in.counts,
                      in.model ? associate_on(*in.model, associated) : AssociateVertex{});
  const std::int64_t on_model = comm.sum(std::int64_t(associated.vertices)),
                     from_file = comm.sum(std::int64_t(associated.from_file));
  const double farthest_in = comm.max(associated.max_distance);
  comm.step([&] {
    for (int r : in.part.triangle_refs) {
      if (r >= kPartFaceId)
        throw InputError(
            fmt::format("{}: surface id {} is reserved under mpirun (ids up to {})", run.input, r, kPartFaceId - 1));
      in.max_ref = std::max(in.max_ref, r);
    }
    if (!run.metric.empty()) {
      clamp_metrics(in.part.metrics, run.bounds);
      check_metric_field(in.part.metrics, run.metric);
    }
  });
  in.max_ref = std::int32_t(comm.max(std::int64_t(in.max_ref)));
  if (talk) {
    const ReadCounts& counts = in.counts;
    fmt::print("distributed: {} ranks read {} vertices, {} tets, {} triangles of {} in slices ({:.2f} s)\n",
               comm.size(), counts.vertices, counts.tets, counts.triangles, run.input, clock.seconds());
    if (in.model)
      fmt::print(
          "distributed: {} boundary vertices associated with {} ({} with the input's parameters), "
          "farthest {:.3g} from its entity\n",
          on_model, in.model->source(), from_file, farthest_in);
    if (!counts.dropped.empty()) {
      std::string names;
      for (const auto& d : counts.dropped) names += (names.empty() ? "" : ", ") + d;
      fmt::print("distributed: not carried under mpirun: {}\n", names);
    }
    std::fflush(stdout);
  }
  return in;
}

// A metric file's field stays the background of the whole run, as in one
// process: every rank holds the input mesh and its metric whole (a rank's
// slice alone would leave the vertices a later round brings it outside),
// so this costs each rank the input's size. None for an analytic metric.
std::unique_ptr<BackgroundMetric> whole_background(const Comm& comm, const DistributedAdapt& run) {
  std::unique_ptr<BackgroundMetric> background;
  if (!run.metric.empty() && run.background && !run.dry_run && run.rounds > 0)
    comm.step([&] {
      const io::MeshData data = io::read_mesh_file(run.input);
      BuildOptions bo;
      bo.source = run.input;
      bo.ridge_angle = kNoRidgeSplit;  // located in only: its surfaces do not matter
      const Mesh whole = build_mesh(data, bo);
      auto field = metric_field_from_sol(io::read_sol(run.metric), data.vertices.size(), run.metric);
      clamp_metrics(field, run.bounds);
      background = std::make_unique<BackgroundMetric>(whole, field);
    });
  return background;
}

// The settings of a part's rounds: the later rounds' (PartRoundRules) and
// the first round's of an adaptation on several parts.
struct RoundSettings {
  PartAdaptSettings later, first;
};

RoundSettings round_settings(const Comm& comm, const DistributedAdapt& run, const Input& in,
                             const MetricFunction* exact, const BackgroundMetric* background) {
  RoundSettings s;
  PartAdaptSettings& settings = s.later;
  settings.background = background;
  settings.options = PartRoundRules{}.applied_to(run.options);
  if (comm.rank() == 0 && log::level() >= log::Level::verbose)
    fmt::print(
        "distributed: each part's rounds after the first flip in up to {} sweeps a quality pass and cycle "
        "down to a {} gain in the unit band (the settings given: {}, {})\n",
        settings.options.polish_sweeps, settings.options.min_conformity_gain, run.options.polish_sweeps,
        run.options.min_conformity_gain);
  settings.policies = run.policies;
  settings.exact = exact;
  settings.default_surface_id = in.max_ref + 1;
  settings.model = in.model.get();
  settings.keep_surface = run.keep_surface;
  // The first round of an adaptation on several parts, on a mesh far from
  // its predicted size, keeps the input's faces between them, coarse where
  // the metric asks for small tets; the next round adapts again around
  // every tet it leaves poor. So it runs the single process's settings and
  // no repair rounds: they cannot lift the tets the kept faces hold (at 1M
  // tets on 2 ranks the round took 7.7 s with four of them and the parts'
  // settings, 6.4 s without).
  s.first = settings;
  s.first.options = PartRoundRules{}.applied_to_first(run.options);
  s.first.options.repair_rounds = 0;
  return s;
}

// A round's figures over all ranks.
struct RoundFigures {
  double volume_before, volume_after;
  Spread tets;
  std::int64_t kept_out, adapted, undone, off_model;
  double in_range, min_q;
};

RoundFigures round_figures(const Comm& comm, const PartAdaptResult& result, const Part& part) {
  RoundFigures f;
  f.volume_before = comm.sum(result.volume_before), f.volume_after = comm.sum(result.volume_after);
  f.tets = spread(comm, std::int64_t(part.tets.size()));
  f.kept_out = comm.sum(result.kept_out), f.adapted = comm.sum(result.adapted);
  f.undone = comm.sum(std::int64_t(result.undone));
  // The quality of the tets adapted this round.
  const double edges = double(comm.sum(result.quality.edges));
  f.in_range = double(comm.sum(result.quality.edges_in_range)) / std::max(1.0, edges);
  f.min_q = comm.min(result.quality.min_quality);
  f.off_model = comm.sum(result.off_model);
  return f;
}

// How long a round's steps took on this rank.
struct RoundTimes {
  double cut = 0, move = 0, adapt = 0, all = 0;
};

void print_round(const DistributedAdapt& run, int it, int round, int parts, bool recut, const RoundFigures& f,
                 std::int64_t unfinished, const RoundTimes& time) {
  fmt::print(
      "  {}round {}: {} tets ({} part{}{}, {} .. {} per rank; {} adapted, {} kept out at pinches) | "
      "adapted: in range {:5.1f}% min Q {:.3f} | {} vertices unfinished{} | volume change {:.2g} | "
      "{}adapt {:.2f} s (rank 0), {:.2f} s in all\n",
      run.iterations > 1 ? fmt::format("iteration {} ", it + 1) : "", round + 1, f.tets.total, parts,
      parts == 1 ? "" : "s", f.undone > 0 ? fmt::format(", {} undone", f.undone) : "", f.tets.low, f.tets.high,
      f.adapted, f.kept_out, 100.0 * f.in_range, f.min_q, unfinished,
      f.off_model > 0 ? fmt::format(" ({} off the model)", f.off_model) : "",
      f.volume_before > 0 ? std::abs(f.volume_after - f.volume_before) / f.volume_before : 0.0,
      recut ? fmt::format("cut {:.2f} s, move {:.2f} s, ", time.cut, time.move) : "no cut, ", time.adapt, time.all);
  std::fflush(stdout);
}

// The iterations' rounds on the part (docs/distributed.md): each cuts and
// moves the mesh (unless what the last left unfinished lies inside
// parts), adapts every part, and says what the next adapts around; the
// adaptation ends when nothing poor is left. Returns the number of parts
// the last round ran on.
int adapt_rounds(const Comm& comm, const DistributedAdapt& run, Part& part, const RoundSettings& s,
                 const CadModel* model, GlobalId next_id, double volume_in, bool talk) {
  const PartAdaptSettings& settings = s.later;
  std::vector<GlobalId> frozen_before;
  int last_parts = comm.size();
  bool inside_parts = false;
  for (int it = 0; it < run.iterations; ++it)
    for (int round = 0; round < run.rounds; ++round) {
      Stopwatch round_clock;
      // A new metric (the first round of an adaptation): every tet.
      if (round == 0) part.focus.clear();
      // Each cut stays away from the faces the round before kept.
      PartitionWeights weights;
      double predicted = 0;
      weights.tets = predicted_tets(comm, part, settings.exact, predicted);
      weights.avoid = frozen_before;
      const double now = double(comm.sum(std::int64_t(part.tets.size())));
      const int parts = parts_for(comm.size(), now, predicted);
      if (parts == 2) weights.heavy = kAvoidBetweenTwo;
      // On a mesh already near its size the tets count as they are: the
      // vertex formula of the metric volume overestimates it in tets
      // across a sharp layer (polar-1: parts 2x apart).
      const bool near_size = predicted > 0.5 * now && predicted < 2.0 * now;
      if (near_size) weights.tets.assign(part.tets.size(), 1);
      // What the last round left unfinished lies inside parts, away from
      // the faces between them, in parts still balanced: the next round
      // adapts around it where it is.
      const bool recut = round == 0 || !inside_parts || parts != last_parts;
      RoundTimes time;
      Stopwatch step_clock;
      time.cut = recut ? move_to_parts(comm, part, weights, parts) : 0.0;
      time.move = step_clock.seconds() - time.cut;
      // The last round a run allows, on a mesh adapted before, is undone on
      // a part where it leaves a tet poorer than it was given (adapt_part):
      // no round after it would adapt there again.
      PartAdaptSettings this_round = round == 0 && parts > 1 && !near_size ? s.first : settings;
      this_round.keep_worst = near_size && round > 0 && round + 1 == run.rounds;
      const auto result = adapt_part(comm, part, this_round, next_id);
      time.adapt = step_clock.seconds() - time.cut - time.move;
      const RoundFigures f = round_figures(comm, result, part);
      const std::int64_t rekept = round > 0 ? held_again(comm, frozen_before, result.held) : -1;
      // The next cut stays away from what this round left unfinished, and
      // the next round adapts only around it: the rest is adapted already.
      frozen_before = unfinished_on_both_sides(comm, part, result.kept_vertices);
      const std::int64_t unfinished = comm.sum(std::int64_t(frozen_before.size()));
      time.all = round_clock.seconds();
      if (talk) print_round(run, it, round, parts, recut, f, unfinished, time);
      // On a model the boundary moves onto it: the volume follows.
      const double volume_now = comm.sum(part_volume(part));
      comm.step([&] {
        const double tolerance = adapted_volume_tolerance(it + 1, run.options.volume_budget);
        if (comm.rank() == 0 && !model && std::abs(volume_now - volume_in) > tolerance * volume_in)
          throw InputError(fmt::format("adapt: the volume moved by {:.3g} relative (at most {:.3g}); nothing written",
                                       std::abs(volume_now - volume_in) / volume_in, tolerance));
      });
      // Nothing left unfinished (one part kept no face), or no tet adapted
      // below kPoorAtKeptFace from the third round on, or from the second
      // when it adapted all the first left unfinished inside parts: this
      // adaptation is done. The tets a round adapts against the faces it
      // keeps are its poorest; the next round has them inside a part.
      last_parts = parts;
      const bool settled = round + 1 >= kFewestRounds || rekept == 0;
      if (parts == 1 || unfinished == 0 || (settled && f.min_q >= kPoorAtKeptFace && f.off_model == 0)) break;
      // Once settled only the poor tets keep the adaptation from ending:
      // the next round adapts around them alone (4.3M tets on 2 ranks: the
      // third round around one sliver's vertices instead of 240).
      if (settled) frozen_before = unfinished_on_both_sides(comm, part, result.poor_vertices);
      if (round + 1 < run.rounds) {  // the next round's tets
        const auto near = tets_near(part, frozen_before, kFocusLayers);
        part.focus.assign(near.begin(), near.end());
        inside_parts = !on_faces_between_parts(comm, part, frozen_before) &&
                       double(f.tets.high) * parts <= kMostWithoutCut * double(f.tets.total);
      }
    }
  return last_parts;
}

// The whole output's figures for the report and the checks before it is
// written.
struct OutputFigures {
  Spread tets;
  double in_range = 0, min_q = 0, mean_q = 0;
  double farthest = 0;  // a boundary vertex's largest distance to its entity
};

// Measured before anything is written: a failure here leaves no output,
// and an output `check --geometry` would refuse (its tolerance) is not
// written.
OutputFigures output_figures(const Comm& comm, const DistributedAdapt& run, const Part& part,
                             const PartAdaptSettings& settings, const CadModel* model) {
  OutputFigures out;
  // The quality (the edges between parts counted on each side), for the
  // report (none with -q, as the single process).
  out.tets = spread(comm, std::int64_t(part.tets.size()));
  QualityTally q;
  if (run.rounds > 0 && run.talk) comm.step([&] { q = part_quality(part, settings); });
  const double edges = double(comm.sum(q.edges));
  out.in_range = double(comm.sum(q.edges_in_range)) / std::max(1.0, edges);
  out.min_q = comm.min(q.min_quality);
  out.mean_q = comm.sum(q.sum_quality) / std::max(1.0, double(out.tets.total));
  // How far the boundary vertices are from their entities (each counted
  // on every rank holding it).
  std::int64_t without = 0;  // vertices of boundary or interface triangles without an entity
  if (model) {
    for (std::size_t v = 0; v < part.geo.size(); ++v)
      if (part.geo[v].valid())
        out.farthest = std::max(out.farthest, (model->value(part.geo[v]) - part.points[v]).norm());
    const VertexIndex index(part.vertex_ids);
    std::vector<bool> counted(part.geo.size(), false);
    for (const auto& f : part.triangles)
      for (GlobalId g : f) {
        const auto v = std::size_t(index.find(g));
        if (!part.geo[v].valid() && !counted[v]) counted[v] = true, ++without;
      }
  }
  out.farthest = comm.max(out.farthest);
  without = comm.sum(without);
  comm.step([&] {
    if (comm.rank() == 0 && (out.farthest > kOnModel || without > 0))
      throw InputError(
          fmt::format("adapt: the boundary is not on {} ({} vertices without an entity, largest distance {:.3g}, "
                      "at most {:.0e}); nothing written",
                      model->source(), without, out.farthest, kOnModel));
  });
  return out;
}

// The mesh, its metric and its .vtu, written by all ranks to temporaries
// and renamed together once all are whole.
WrittenCounts write_outputs(const Comm& comm, const DistributedAdapt& run, const Part& part,
                            const PartAdaptSettings& settings, const CadModel* model) {
  const VertexNumbering numbering = number_vertices(comm, part);
  WrittenCounts written;
  StagedOutputs outputs(comm);
  const bool text = io::format_of(run.output) == io::FileFormat::mesh;
  outputs.add(text ? write_part_text(comm, part, numbering, run.output, run.version, model, &written)
                   : write_part(comm, part, numbering, run.output, run.version, model, &written));
  if (!run.metric_out.empty()) {
    const auto metric_of = [&](std::size_t v) {
      return settings.exact ? (*settings.exact)(part.points[v]) : part.metrics[v];
    };
    outputs.add(io::format_of(run.metric_out) == io::FileFormat::sol
                    ? write_part_metric_text(comm, numbering, metric_of, run.metric_out, written.version)
                    : write_part_metric(comm, numbering, metric_of, run.metric_out, written.version));
  }
  if (!run.vtu.empty()) outputs.add(write_part_vtu(comm, part, numbering, run.vtu));
  outputs.commit();
  return written;
}

void print_output(const Comm& comm, const DistributedAdapt& run, const WrittenCounts& written, const OutputFigures& f,
                  const CadModel* model, const Stopwatch& clock) {
  fmt::print("wrote {}: {} vertices, {} triangles, {} tets (libMeshb v{}) on {} ranks ({:.2f} s in all)\n", run.output,
             written.vertices, written.triangles, written.tets, written.version, comm.size(), clock.seconds());
  if (!run.metric_out.empty())
    fmt::print("wrote {}: the metric at its {} vertices\n", run.metric_out, written.vertices);
  if (!run.vtu.empty()) fmt::print("wrote {}: its tets for ParaView\n", run.vtu);
  fmt::print("tets per rank {} .. {}, the most {:.3f} x the mean\n", f.tets.low, f.tets.high,
             double(f.tets.high) * comm.size() / double(std::max<std::int64_t>(1, f.tets.total)));
  if (run.rounds > 0)
    fmt::print("edges in [1/sqrt2, sqrt2] {:.2f}%, mean ratio min {:.4f} mean {:.4f}\n", 100.0 * f.in_range, f.min_q,
               f.mean_q);
  if (model)
    fmt::print("boundary vertices on {}: largest distance to their entity {:.3g}\n", model->source(), f.farthest);
}

// The whole mesh moved to all ranks' parts, each tet counting one.
void spread_over_ranks(const Comm& comm, Part& part) {
  PartitionWeights weights;
  weights.tets.assign(part.tets.size(), 1);
  move_to_parts(comm, part, weights, comm.size());
}

}  // namespace

void adapt_distributed(const Comm& comm, const DistributedAdapt& run) {
  const bool talk = run.talk && comm.rank() == 0;
  Stopwatch clock;
  Input in = read_input(comm, run, talk, clock);
  Part& part = in.part;
  MetricFunction exact;
  if (run.analytic)
    exact = [kind = *run.analytic, b = run.bounds](const Point& p) {
      return b.active() ? clamp_metric(evaluate(kind, p), b) : evaluate(kind, p);
    };
  const std::unique_ptr<BackgroundMetric> background = whole_background(comm, run);
  const RoundSettings settings = round_settings(comm, run, in, run.analytic ? &exact : nullptr, background.get());
  const double predicted_out = predicted_output(comm, part, settings.later.exact, in.counts.tets);
  comm.step([&] {
    if (comm.rank() == 0 && run.max_tets > 0 && !(predicted_out <= run.max_tets))
      throw InputError(fmt::format("adapt: the metric predicts about {:.3g} tets; the limit is {:.3g} tets ({})",
                                   predicted_out, run.max_tets, run.max_tets_reason));
  });
  if (run.dry_run) {
    if (comm.rank() == 0)
      fmt::print("adapt: {} vertices, {} tets in; about {:.3g} tets out on {} ranks, about {:.3g} a rank\n",
                 in.counts.vertices, in.counts.tets, predicted_out, comm.size(), predicted_out / comm.size());
    return;
  }
  const double volume_in = comm.sum(part_volume(part));
  // --rounds 0: cut and move once, no adaptation (the parallel read and
  // write round trip).
  if (run.rounds == 0) spread_over_ranks(comm, part);
  const int last_parts =
      run.rounds > 0 ? adapt_rounds(comm, run, part, settings, in.model.get(), in.counts.vertices, volume_in, talk)
                     : comm.size();
  // The output spread over every rank when the last round ran on fewer.
  if (run.rounds > 0 && last_parts < comm.size() && comm.sum(std::int64_t(part.tets.size())) >= comm.size())
    spread_over_ranks(comm, part);
  const OutputFigures figures = output_figures(comm, run, part, settings.later, in.model.get());
  const WrittenCounts written = write_outputs(comm, run, part, settings.later, in.model.get());
  if (talk) print_output(comm, run, written, figures, in.model.get(), clock);
}

}  // namespace metrica::distributed
