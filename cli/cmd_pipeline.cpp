// metrica pipeline: a pipeline composed on the command line from the
// registry's stage kinds (pipeline/stage_registry.hpp), as Python's
// Pipeline composes one, run on a mesh and written as adapt writes.
#include "adaptation_report.hpp"
#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/pipeline/composed_pipeline.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <memory>

namespace metrica::cli {

namespace {

// The stage kinds and their options, as the help lists them.
std::string stage_kinds_text() {
  std::string text = "Operations and their options:\n";
  for (const StageKindInfo& k : stage_kind_infos()) {
    text += fmt::format("  {:<10} {}\n", k.op, k.help);
    for (const StageOption& opt : k.options) text += fmt::format("    {}: {}, {}\n", opt.name, opt.help, opt.domain());
  }
  return text;
}

ComposedPipeline composed_from(const Options& o) {
  ComposedPipeline p;
  o.as_usage([&] {
    if (o.has("cycle")) p.cycle = parse_stage_list(o.get<std::string>("cycle"), "--cycle");
    if (o.has("polish")) p.polish = parse_stage_list(o.get<std::string>("polish"), "--polish");
    if (o.has("repair")) p.repair = parse_stage_list(o.get<std::string>("repair"), "--repair");
  });
  AdaptOptions rules;
  for (const AdaptSetting& s : pipeline_rule_settings()) read_setting(o, s, rules);
  p.rules = rules;
  o.as_usage([&] { check_composed(p); });
  return p;
}

struct PipelineRun {
  Mesh mesh;
  int input_version = 0;
};

// One run from the input (read again on each call), up to the checks of
// the adapted mesh.
PipelineRun run_input(const Options& o, const ComposedPipeline& p, const std::string& concurrency,
                      const std::optional<AnalyticMetric>& analytic) {
  auto loaded = load_mesh(o.get<std::string>("input"));
  PipelineRun out{std::move(loaded.mesh), loaded.data.version};
  Mesh& mesh = out.mesh;
  const double volume = mesh.volume();
  const std::size_t input_vertices = loaded.data.vertices.size();
  loaded.data = io::MeshData{};
  const std::vector<Sym6> field = metric_at_vertices(o, mesh, analytic, MetricBounds{}, input_vertices);
  MetricFunction exact;
  if (analytic) exact = [kind = *analytic](const Point& x) { return evaluate(kind, x); };
  const double predicted =
      check_predicted_size(o, analytic ? sampled_complexity(mesh, exact) : complexity(mesh, field), "the metric");
  if (o.dry_run()) {
    fmt::print("pipeline: {} vertices, {} tets in; about {:.3g} tets out; {} cycle, {} polish, {} repair stages\n",
               count_text(mesh.num_vertices()), count_text(mesh.num_tets()), predicted, p.cycle.size(), p.polish.size(),
               p.repair.size());
    return out;
  }
  assign_metric(mesh, field);
  AdaptInputs inputs;  // a file's field: run_composed keeps it on the input mesh
  if (analytic) inputs.metric = &exact;
  const bool talk = log::level() >= log::Level::normal;
  if (talk) {
    inputs.on_cycle = print_cycle;
    fmt::print(
        "running the pipeline on {} vertices, {} tets ({})\n", count_text(mesh.num_vertices()),
        count_text(mesh.num_tets()),
        concurrency == Serial::name ? std::string("serial") : fmt::format("speculative, {} threads", thread_count()));
  }
  const AdaptReport report = run_composed(mesh, p, inputs, concurrency);
  if (talk) {
    fmt::print("  {:.2f} s\n", report.seconds);
    print_operator_stats(report, concurrency == Serial::name, thread_count());
  }
  require_adapted(mesh, nullptr, volume, adapted_volume_tolerance(1, AdaptOptions{}.volume_budget),
                  sweep_runner(mesh.tet_capacity(), concurrency == Serial::name));
  return out;
}

}  // namespace

int run_pipeline(const std::vector<std::string>& args) {
  Options o("pipeline", "[-i] MESH (-m METRIC | --analytic NAME) [-o] OUTPUT --cycle STAGES [options]",
            "Runs a pipeline composed here from the stages below: the --cycle stages in a row until the\n"
            "rules stop them (--cycles, --min-change, --min-conformity-gain), then the --polish stages\n"
            "--quality-passes times, then the --repair stages while a tet is below --repair-below (at most\n"
            "--repair-rounds). A list is stages separated by commas, each [NAME=]OP[:OPTION=VALUE]...;\n"
            "NAME (the operation's by default) is the stage's key in the report and in the incremental\n"
            "passes, so a list holds each name once. The same stages as Python's metrica.Pipeline, in the\n"
            "log-Euclidean space with filtered predicates, the boundary on the input's facets (no\n"
            "--geometry); the output is checked and written as metrica adapt writes it, and a run on\n"
            "threads that fails its check is made again serially.\n\n" +
                stage_kinds_text() +
                "\nExamples:\n"
                "  metrica pipeline cube.meshb --analytic polar-1 -o out.meshb \\\n"
                "      --cycle collapse,split,flip:criterion=metric-delaunay,smooth:below=0.3 \\\n"
                "      --polish flip,smooth:below=1 --cycles 8\n"
                "  metrica pipeline in.meshb -m in.solb -o out.meshb --cycle \"collapse, split, \\\n"
                "      delaunay=flip:criterion=metric-delaunay, weight=flip:criterion=edge-weight\"");
  const AdaptOptions d;
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.output(
      "adapted mesh (.mesh, .meshb, .msh, .vtu, .su2)",
      {io::FileFormat::mesh, io::FileFormat::meshb, io::FileFormat::msh, io::FileFormat::vtu, io::FileFormat::su2});
  o.metric_source("metric at the input's vertices (.sol, .solb)");
  o.add()("cycle", po::value<std::string>()->value_name("STAGES"), "the stages of one adaptation cycle")(
      "polish", po::value<std::string>()->value_name("STAGES"), "the stages of one quality pass")(
      "repair", po::value<std::string>()->value_name("STAGES"), "the stages of one repair round")(
      "concurrency", po::value<std::string>()->default_value(std::string(Concurrencies::at<0>::name))->value_name("C"),
      "speculative (on --threads threads) or serial (one thread, the same output to the bit on every run)");
  for (const AdaptSetting& s : pipeline_rule_settings()) declare_setting(o, s, d);
  o.format_version("libMeshb version to write (default: the input's)");
  o.msh_binary();
  max_tets_option(o);
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  const auto output = o.required("output", "the output mesh (-o)");
  o.one_of({"metric", "analytic"}, "one of -m METRIC or --analytic NAME");
  PolicyChoice policies;
  policies.concurrency = o.get<std::string>("concurrency");
  o.as_usage([&] { check_policy_choice(policies); });
  const ComposedPipeline p = composed_from(o);
  const auto analytic = o.named("analytic", analytic_metric_from_name);

  Stopwatch clock;
  PipelineRun adapted =
      adapt_or_again_serially(policies, fmt::format("from {} under --concurrency serial", input),
                              [&](const PolicyChoice& c) { return run_input(o, p, c.concurrency, analytic); });
  if (o.dry_run()) return kOk;
  const Mesh& mesh = adapted.mesh;
  const PartRunner sweeps = sweep_runner(mesh.tet_capacity(), policies.concurrency == Serial::name);
  auto data = extract_mesh_data(mesh);
  data.version = adapted.input_version;
  io::write_mesh_file(output, data, o.format_version(), sweeps, io::FileFormat::mesh, o.msh_encoding());
  if (log::level() >= log::Level::normal) {
    // The report first: it throws on a non-finite measure, and the run
    // then fails with nothing written.
    const QualityReport report = quality_report(mesh, LogEuclidean::name, {.run = sweeps, .cached_quality = true});
    fmt::print("wrote {} ({:.2f} s in all)\n", output, clock.seconds());
    fmt::print("{}", format_report(report));
  }
  return kOk;
}

}  // namespace metrica::cli
