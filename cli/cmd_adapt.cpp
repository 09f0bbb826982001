#include "adaptation_report.hpp"
#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/vtu.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#ifdef METRICA_HAS_MPI
#include <metrica/distributed/distributed_adapt.hpp>
#include <metrica/distributed/launch.hpp>
#endif

namespace metrica::cli {

namespace {

// The command's options; the defaults shown and used are the library's
// (AdaptOptions{}).
void declare_adapt_options(Options& o) {
  const AdaptOptions d;
  const PolicyChoice policies;
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.output(
      "adapted mesh (.mesh, .meshb, .msh, .vtu, .su2)",
      {io::FileFormat::mesh, io::FileFormat::meshb, io::FileFormat::msh, io::FileFormat::vtu, io::FileFormat::su2});
  o.metric_source("metric at the input's vertices (.sol, .solb)");
  o.add()("interpolate-from", po::value<std::string>()->default_value("background")->value_name("FROM"),
          "with -m, where a new or moved vertex takes its metric: background (the input mesh and its "
          "metric, kept for the whole run: the log-Euclidean interpolation of the field you gave, at the "
          "vertex's position) or parents (interpolated by --space from the vertices it is made from; a moved "
          "vertex keeps its metric). The closing report and --metric-out are in the background field "
          "either way");
  o.add()("iterations", po::value<int>()->default_value(1)->value_name("N"),
          "adaptations in a row, the metric re-evaluated between them (--analytic only)")(
      "space", po::value<std::string>()->default_value(policies.space)->value_name("S"),
      "metric interpolation: log-euclidean, anisotropic, isotropic")(
      "precision", po::value<std::string>()->default_value(policies.precision)->value_name("P"),
      "the metric-Delaunay criterion's insphere signs (the centroid rule's flips): filtered (exact when "
      "it matters), exact, fast (plain double); orientations are decided alike under every precision")(
      "concurrency", po::value<std::string>()->default_value(policies.concurrency)->value_name("C"),
      "speculative (every operator on --threads threads, lock-free per-vertex try-locks) or serial "
      "(one thread, the same output to the bit on every run)")(
      "points", po::value<std::string>()->default_value(to_string(d.points))->value_name("RULE"),
      "point creation: edge (split long edges at their metric midpoint) or centroid (the centroids "
      "of tets with a long edge, moved to a boundary face or ridge they encroach)");
  for (const AdaptSetting& s : adapt_settings()) declare_setting(o, s, d);
  o.add()("hmin", po::value<double>()->value_name("H"), "clamp the metric's sizes to at least H")(
      "hmax", po::value<double>()->value_name("H"), "clamp the metric's sizes to at most H")(
      "geometry", po::value<std::string>()->value_name("MODEL"),
      "CAD model the boundary lies on (.step .stp .iges .igs .brep .geo): new boundary vertices go on it")(
      "keep-surface",
      "keep the boundary and the internal surfaces exactly as they are (no vertex moved, added or removed on "
      "them, no face flipped) and adapt the volume only")(
      "ridge-angle", po::value<double>()->value_name("DEG"),
      "split every surface into surfaces at the edges where the boundary turns by more than DEG degrees "
      "(those edges become ridges, where ridges meet corners); 180 splits nothing. Without it, only a "
      "boundary given without surface ids (a mesh of points and tets) or with one id for all of it is "
      "split so, at 45 degrees");
  o.add()("rounds", po::value<int>()->default_value(5)->value_name("N"),
          "under mpirun: at most N cuts of the mesh per adaptation; each rank adapts its part with the faces "
          "between parts kept; each later cut stays away from what the round before left unfinished (poor "
          "tets, off-size edges at kept faces) and its round adapts only around it; the rounds end when "
          "nothing is left or, from the third on, no tet adapted has mean ratio below 0.5 "
          "(docs/distributed.md); 0: cut, move and write without adapting");
  o.output_option("metric-out", "also write the metric at the output's vertices (.sol, .solb)",
                  {io::FileFormat::sol, io::FileFormat::solb});
  o.output_option("vtu", "also write the adapted mesh for ParaView (.vtu)", {io::FileFormat::vtu});
  o.format_version("libMeshb version to write (default: the input's)");
  o.msh_binary();
  max_tets_option(o);
}

// The adaptation's settings from the command line (checked).
AdaptOptions adapt_options_from(const Options& o) {
  AdaptOptions ao;
  for (const AdaptSetting& s : adapt_settings()) read_setting(o, s, ao);
  ao.points = *o.named("points", point_rule_from_name);
  o.as_usage([&] { check_length_band(ao, "--min-length", "--max-length"); });
  return ao;
}

// The adapted mesh passes require_adapted (else NotAdapted, nothing
// written); on a model the distance to it is printed first.
void check_adapted(const Mesh& mesh, const CadModel* model, double volume, double volume_tolerance,
                   const PartRunner& sweeps, bool talk) {
  if (model && talk) fmt::print("{}\n", model_distance_text(mesh, *model));
  require_adapted(mesh, model, volume, volume_tolerance, sweeps);
  if (log::level() >= log::Level::verbose) {
    const double adapted = mesh.volume();
    log::info("volume {:.17g}, relative change {:.3g}", adapted, std::abs(adapted - volume) / volume);
  }
}

// The mesh (and --vtu, --metric-out) written, each to a temporary renamed
// when the whole run succeeded.
void write_outputs(const Options& o, const Mesh& mesh, const CadModel* model, const std::string& output,
                   int input_version, const PartRunner& sweeps) {
  {
    // The writers' copy of the mesh (25 bytes per tet) is dropped before
    // anything else is built beside the mesh: at the end of a run the
    // copy and the report's edge buckets together were the peak.
    auto data = extract_mesh_data(mesh);
    data.version = input_version;
    if (model) complete_geometry_records(data, *model);
    io::write_mesh_file(output, data, o.format_version(), sweeps, io::FileFormat::mesh, o.msh_encoding());
    if (o.has("vtu")) io::write_mesh_file(o.get<std::string>("vtu"), data, 0, {}, io::FileFormat::vtu);
  }
  if (o.has("metric-out")) {
    auto sol = metric_sol(mesh);
    sol.version = input_version;
    io::write_sol(o.get<std::string>("metric-out"), sol, o.format_version(), sweeps);
  }
}

#ifdef METRICA_HAS_MPI
// Under mpirun with several ranks: the distributed executor. What it does
// not carry yet is refused up front.
int run_distributed(const Options& o, const AdaptOptions& ao, const PolicyChoice& policies,
                    const std::optional<AnalyticMetric>& analytic, const MetricBounds& bounds, int iterations) {
  if (o.has("ridge-angle"))
    throw UsageError(
        "adapt: --ridge-angle is not taken under mpirun (the ranks read the surfaces as given): give the "
        "surfaces as Triangles with ids, or adapt on one process");
  distributed::DistributedAdapt run;
  run.input = o.get<std::string>("input");
  run.output = o.get<std::string>("output");
  if (io::format_of(run.output) != io::FileFormat::meshb && io::format_of(run.output) != io::FileFormat::mesh)
    throw UsageError(fmt::format(
        "adapt: under mpirun the output is one .meshb or .mesh written by all ranks (got {}; metrica convert "
        "writes the other formats)",
        run.output));
  if (o.has("metric")) {
    run.metric = o.get<std::string>("metric");
    if (io::format_of(run.metric) != io::FileFormat::solb && io::format_of(run.metric) != io::FileFormat::sol)
      throw UsageError(fmt::format("adapt: {}: the metric must be a .sol or .solb", run.metric));
  }
  if (o.has("geometry")) run.geometry = o.get<std::string>("geometry");
  if (o.has("metric-out")) {
    run.metric_out = o.get<std::string>("metric-out");
    if (io::format_of(run.metric_out) != io::FileFormat::solb && io::format_of(run.metric_out) != io::FileFormat::sol)
      throw UsageError(fmt::format(
          "adapt: under mpirun --metric-out is one .solb or .sol written by all ranks (got {})", run.metric_out));
  }
  if (o.has("vtu")) run.vtu = o.get<std::string>("vtu");
  run.keep_surface = o.has("keep-surface");
  run.background = o.get<std::string>("interpolate-from") == "background";
  // The ranks on one node share its memory (nodes taken alike).
  run.max_tets = o.has("max-tets") ? o.positive("max-tets")
                                   : double(default_max_tets()) * distributed::MpiRuntime::size() /
                                         std::max(1, distributed::MpiRuntime::local_size());
  run.max_tets_reason =
      o.has("max-tets") ? "--max-tets" : "--max-tets N raises it; the default is what 90% of the nodes' memory holds";
  run.dry_run = o.dry_run();
  run.analytic = analytic;
  run.bounds = bounds;
  run.options = ao;
  run.policies = policies;
  run.iterations = iterations;
  run.rounds = o.in_range("rounds", 0, 100);
  run.version = o.format_version();
  if (run.version == 1) throw UsageError("adapt: under mpirun the output is libMeshb version 2, 3 or 4 (64-bit reals)");
  run.talk = log::level() >= log::Level::normal;
  // The node's cores shared among its ranks unless --threads or
  // OMP_NUM_THREADS chooses; each rank keeps its share (the other ranks
  // are the load it would follow).
  if (!o.has("threads") && std::getenv("OMP_NUM_THREADS") == nullptr)
    set_thread_count(std::max(1, core_count() / distributed::MpiRuntime::local_size()));
  Speculative::settings().follow_load = false;
  distributed::adapt_distributed(distributed::Comm{}, run);
  return kOk;
}
#endif

// One adaptation of the input (read again on each call), up to the checks
// of the adapted mesh: what is written, or NotAdapted when a check fails.
struct Adapted {
  Mesh mesh;
  std::unique_ptr<CadModel> model;
  int input_version = 0;
  // Seconds of the steps around the adaptation (adapt -v's account).
  double load_seconds = 0, metric_seconds = 0, adapt_seconds = 0, check_seconds = 0;
};
Adapted adapt_input(const Options& o, const AdaptOptions& ao, const PolicyChoice& policies,
                    const std::optional<AnalyticMetric>& analytic, const MetricBounds& bounds, int iterations) {
  const auto input = o.get<std::string>("input");
  const bool serial = policies.concurrency == Serial::name;
  AdaptInputs inputs;
  const std::string interpolate_from = o.get<std::string>("interpolate-from");
  Adapted out;
  Stopwatch step;
  auto loaded = load_mesh(input, Valid::required, ridge_angle(o));
  Mesh& mesh = out.mesh;
  mesh = std::move(loaded.mesh);
  const double volume = mesh.volume();
  std::unique_ptr<CadModel>& model = out.model;
  if (o.has("geometry")) {
    model = open_geometry(o.get<std::string>("geometry"), mesh, &loaded.data, true);
    inputs.model = model.get();
  }
  if (o.has("keep-surface")) mesh.keep_surface();
  // The input's arrays are in the mesh now: only its vertex count and
  // version are read again.
  const std::size_t input_vertices = loaded.data.vertices.size();
  out.input_version = loaded.data.version;
  loaded.data = io::MeshData{};
  // A metric file's field, kept on the input mesh (built once the field is
  // assigned, before any work).
  std::unique_ptr<BackgroundMetric> background;
  MetricFunction exact;
  if (analytic) {
    if (bounds.active())
      exact = [kind = *analytic, bounds](const Point& p) { return clamp_metric(evaluate(kind, p), bounds); };
    else
      exact = [kind = *analytic](const Point& p) { return evaluate(kind, p); };
    inputs.metric = &exact;
  }
  const bool talk = log::level() >= log::Level::normal;
  if (talk) inputs.on_cycle = print_cycle;
  out.load_seconds = step.seconds();
  for (int it = 0; it < iterations; ++it) {
    step = Stopwatch();
    const std::vector<Sym6> field = metric_at_vertices(o, mesh, analytic, bounds, input_vertices);
    if (it == 0) {
      // The size is predicted once, before any work. An analytic metric is
      // sampled inside the tets (the vertex formula overestimates it on a
      // coarse start mesh).
      const double c = analytic ? sampled_complexity(mesh, exact) : complexity(mesh, field);
      const double predicted = check_predicted_size(o, c, "the metric");
      if (o.dry_run()) {
        fmt::print("adapt: {} vertices, {} tets in; about {:.3g} tets out (complexity x {}), about {} of memory\n",
                   count_text(mesh.num_vertices()), count_text(mesh.num_tets()), predicted, kTetsPerComplexity,
                   bytes_text(predicted * kBytesPerTet));
        return out;
      }
    }
    assign_metric(mesh, field);
    if (!analytic && it == 0) {
      background = std::make_unique<BackgroundMetric>(mesh);
      if (interpolate_from == "background") inputs.background = background.get();
    }
    if (talk)
      fmt::print("{}adapting {} vertices, {} tets ({} space, {} predicates, {} points, {})\n",
                 iterations > 1 ? fmt::format("iteration {}: ", it + 1) : "", count_text(mesh.num_vertices()),
                 count_text(mesh.num_tets()), policies.space, policies.precision, to_string(ao.points),
                 serial ? std::string("serial")
                 : log::level() >= log::Level::verbose
                     ? Speculative::describe()
                     : fmt::format("speculative, {} thread{}", thread_count(), thread_count() == 1 ? "" : "s"));
    out.metric_seconds += step.seconds();
    const auto report = adapt_by_name(mesh, ao, policies, inputs);
    out.adapt_seconds += report.seconds;
    if (talk)
      fmt::print("  {:.2f} s: {} collapses, {} splits, {} flips, {} moves\n", report.seconds,
                 count_text(report.ops.get("collapse").applied + report.ops.get("lift").applied),
                 count_text(report.ops.get("split").applied + report.ops.get("centroids").applied),
                 count_text(report.ops.get("flip").applied + report.ops.get("delaunay").applied),
                 count_text(report.ops.get("smooth").applied));
    if (talk && (!serial || log::level() >= log::Level::verbose)) print_operator_stats(report, serial, thread_count());
  }
  step = Stopwatch();
  const PartRunner sweeps = sweep_runner(mesh.tet_capacity(), serial);
  if (background) {
    // The report and --metric-out in the field the user gave: the
    // background at every output vertex.
    const std::size_t outside = background->assign(mesh, sweeps);
    if (talk && outside > 0)
      fmt::print("{} of {} output vertices outside the input mesh: the nearest input tet's metric, clamped\n",
                 count_text(outside), count_text(mesh.num_vertices()));
    background.reset();  // not beside the writers' copy of the mesh
  }
  check_adapted(mesh, model.get(), volume, adapted_volume_tolerance(iterations, ao.volume_budget), sweeps, talk);
  out.check_seconds = step.seconds();
  return out;
}

}  // namespace

int run_adapt(const std::vector<std::string>& args) {
  Options o("adapt", "[-i] MESH (-m METRIC | --analytic NAME) [-o] OUTPUT [options]",
            "Adapts a tetrahedral mesh to a metric: cycles of edge collapse, edge split, flips and vertex\n"
            "smoothing until the mesh is a unit mesh (edge lengths near 1 in the metric), then a quality\n"
            "phase of flips and smoothing, and repair rounds around any tet still below --repair-below.\n"
            "Prints one line per cycle, pass and round (vertices, tets, applied/tried per operator with\n"
            "its time, share of edges in [1/sqrt2, sqrt2], worst mean ratio) and ends with the UGAWG\n"
            "quality report; -v adds each operator's counts and where the time went (the passes, in\n"
            "and outside their parallel loops, the cycles' ends, the steps around the adaptation).\n"
            "With --analytic, new vertices take the exact metric, and\n"
            "--iterations N repeats the adaptation N times, re-evaluating the metric on the new mesh each\n"
            "time (the UGAWG loop). The output is checked with validate() before it is written; if a\n"
            "run on threads ends with a check that fails, the run is made again from the input under\n"
            "--concurrency serial (a warning says so), and nothing is written only if that fails too.\n"
            "By default every operator runs on all cores (--threads N to choose, --concurrency serial\n"
            "for one thread and an output that is the same to the bit on every run).\n"
            "With --geometry MODEL (.step, .iges, .brep, .geo: any file gmsh opens) new boundary vertices\n"
            "are placed on the CAD model, not on the input's facets: the mesh's surface ids must be the\n"
            "model's surface tags, and each boundary vertex is associated with its model vertex, curve\n"
            "or surface (from the input's VerticesOnGeometric* records when the model's point there is\n"
            "the vertex, else by projection: another kernel's parameters are checked, not trusted); the\n"
            "input's distance to the model is printed, vertices off it go onto it in the first stage,\n"
            "and the output .meshb carries the association for the next run.\n"
            "A mesh without boundary triangles (points and tets only), or with one surface id for all\n"
            "of its boundary, is split into surfaces at the edges sharper than 45 degrees, which become\n"
            "ridges (Mmg's -ar; --ridge-angle DEG splits every surface so, 180 none).\n"
            "Regions (tet references), internal surfaces (triangles between two tets) and the input's\n"
            "RequiredVertices, RequiredEdges and RequiredTriangles are kept; --keep-surface keeps the\n"
            "whole surface and adapts the volume only.\n\n"
            "Examples:\n"
            "  metrica adapt cube-linear-00.meshb -m cube-linear-00.solb -o adapted.meshb\n"
            "  metrica adapt cube.meshb --analytic polar-1 --iterations 5 -o polar1.meshb --vtu polar1.vtu\n"
            "  metrica adapt cube.meshb --analytic polar-2 --points centroid -o polar2.meshb\n"
            "  metrica adapt cube.meshb --analytic linear --threads 2 -o linear.meshb\n"
            "  metrica adapt cube-cylinder.meshb --geometry cube-cylinder.step --analytic polar-2 -o cc.meshb");
  declare_adapt_options(o);
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  const auto output = o.required("output", "the output mesh (-o)");
  o.one_of({"metric", "analytic"}, "one of -m METRIC or --analytic NAME");
  const int iterations = o.in_range("iterations", 1, 1000);
  if (iterations > 1 && !o.has("analytic"))
    throw UsageError("adapt: --iterations needs --analytic (a metric file holds values at the input's vertices only)");
  const PolicyChoice policies{o.get<std::string>("space"), o.get<std::string>("precision"),
                              o.get<std::string>("concurrency")};
  o.as_usage([&] { check_policy_choice(policies); });
  const bool serial = policies.concurrency == Serial::name;

  const AdaptOptions ao = adapt_options_from(o);
  const MetricBounds bounds = o.size_bounds();
  const auto analytic = o.named("analytic", analytic_metric_from_name);
  const std::string interpolate_from = o.get<std::string>("interpolate-from");
  if (interpolate_from != "background" && interpolate_from != "parents")
    throw UsageError(fmt::format("adapt: --interpolate-from is background or parents (got '{}')", interpolate_from));
#ifdef METRICA_HAS_MPI
  if (distributed::MpiRuntime::size() > 1) return run_distributed(o, ao, policies, analytic, bounds, iterations);
#endif

  Stopwatch clock;
  const bool talk = log::level() >= log::Level::normal;
  // A threaded run that fails its end check is made again serially from
  // the input read again (adapted_check.hpp).
  Adapted adapted = adapt_or_again_serially(
      policies, fmt::format("from {} under --concurrency serial", input),
      [&](const PolicyChoice& p) { return adapt_input(o, ao, p, analytic, bounds, iterations); });
  if (o.dry_run()) return kOk;
  Mesh& mesh = adapted.mesh;
  const auto& model = adapted.model;
  const int input_version = adapted.input_version;
  const PartRunner sweeps = sweep_runner(mesh.tet_capacity(), serial);
  Stopwatch step;
  write_outputs(o, mesh, model.get(), output, input_version, sweeps);
  const double write_seconds = step.seconds();
  if (talk) {
    // quality_report throws on a non-finite value: the run then fails and
    // its staged outputs are dropped (so the report comes before "wrote").
    // The quality cache holds the mean ratios of this space: adapt kept it
    // (a background's assign cleared it, and the report fills it again).
    step = Stopwatch();
    const QualityReport report = quality_report(mesh, policies.space, {.run = sweeps, .cached_quality = true});
    const double report_seconds = step.seconds(), all = clock.seconds();
    fmt::print("wrote {} ({:.2f} s in all)\n", output, all);
    if (log::level() >= log::Level::verbose) {
      // The steps around the adaptation run on one thread but the checks'
      // and the report's sweeps.
      const double around =
          adapted.load_seconds + adapted.metric_seconds + adapted.check_seconds + write_seconds + report_seconds;
      fmt::print(
          "time: read and build {:.2f} s, metric {:.2f} s, adaptation {:.2f} s, checks {:.2f} s, write {:.2f} s, "
          "report {:.2f} s; around the adaptation {:.2f} s ({:.1f}% of {:.2f} s)\n",
          adapted.load_seconds, adapted.metric_seconds, adapted.adapt_seconds, adapted.check_seconds, write_seconds,
          report_seconds, around, 100.0 * around / std::max(all, 1e-9), all);
    }
    fmt::print("{}", format_report(report));
  }
  return kOk;
}

}  // namespace metrica::cli
