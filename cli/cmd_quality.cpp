#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/metrics/space.hpp>

#include <fmt/core.h>

#include <optional>

namespace metrica::cli {

int run_quality(const std::vector<std::string>& args) {
  Options o("quality", "[-i] MESH (-m METRIC | --analytic NAME) [--csv FILE]",
            "Prints the UGAWG quality report of a mesh in a metric: counts; min / mean / max of the edge\n"
            "length (UGAWG formula) and of the mean ratio (metric at the tet centroid); the share of edges\n"
            "in [1/sqrt2, sqrt2]; the share of tets with Q < 0.1 and < 0.3; the complexity and\n"
            "vertices / complexity; histograms of lengths (log2 bins) and of Q.\n\n"
            "With --metric-mesh M the metric is given at the vertices of M (a solver's metric on the mesh\n"
            "it ran on): the mesh is measured in its log-Euclidean P1 interpolation, exp(sum l_i log M_i) in\n"
            "the tet of M holding each vertex (the nearest tet, clamped, for a vertex outside M).\n\n"
            "Examples:\n"
            "  metrica quality cube-linear-00.meshb -m cube-linear-00.solb\n"
            "  metrica quality adapted.meshb -m solver-metric.solb --metric-mesh solver.meshb\n"
            "  metrica quality adapted.meshb --analytic polar-1 --csv report.csv");
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.metric_source("metric (.sol, .solb)");
  o.add()("space", po::value<std::string>()->default_value(std::string(Spaces::at<0>::name))->value_name("S"),
          "metric interpolation for Q: log-euclidean, anisotropic, isotropic")(
      "hmin", po::value<double>()->value_name("H"), "clamp the metric's sizes to at least H")(
      "hmax", po::value<double>()->value_name("H"), "clamp the metric's sizes to at most H")(
      "metric-mesh", po::value<std::string>()->value_name("MESH"),
      "the mesh whose vertices -m gives the metric at (default: MESH itself)");
  o.output_option("csv", "also write the report as CSV (section,key,lo,hi,value)", {});
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  o.one_of({"metric", "analytic"}, "one of -m METRIC or --analytic NAME");
  const auto space = o.get<std::string>("space");
  if (!Spaces::contains(space))
    throw UsageError(fmt::format("quality: unknown space '{}' ({})", space, Spaces::names()));
  const MetricBounds bounds = o.size_bounds();
  const auto analytic = o.named("analytic", analytic_metric_from_name);

  if (o.has("metric-mesh") && analytic)
    throw UsageError("quality: --metric-mesh goes with -m (an analytic metric is known everywhere)");
  auto loaded = load_mesh(input);
  // The mesh the metric's values are at: the input, or --metric-mesh.
  std::optional<LoadedMesh> other;
  if (o.has("metric-mesh")) other = load_mesh(o.get<std::string>("metric-mesh"));
  const LoadedMesh& on = other ? *other : loaded;
  std::vector<Sym6> field;
  if (analytic) {
    field = analytic_metric_field(*analytic, loaded.data.vertices);
  } else {
    const auto path = o.get<std::string>("metric");
    field = metric_field_from_sol(io::read_sol(path), on.data.vertices.size(), path);
  }
  clamp_metrics(field, bounds);
  check_metric_field(field, analytic ? fmt::format("metric '{}'", to_string(*analytic)) : o.get<std::string>("metric"));
  if (o.dry_run()) return kOk;
  if (other) {
    const BackgroundMetric background(other->mesh, field);
    const std::size_t outside = background.assign(loaded.mesh);
    if (outside > 0 && log::level() >= log::Level::normal)
      fmt::print("{} of {} vertices outside {} (the nearest tet's metric, clamped)\n", count_text(outside),
                 count_text(loaded.mesh.num_vertices()), o.get<std::string>("metric-mesh"));
  } else {
    assign_metric(loaded.mesh, field);
  }
  const auto report = quality_report(loaded.mesh, space, {.run = sweep_runner(loaded.mesh.tet_capacity())});
  if (o.has("csv")) io::write_file_atomically(o.get<std::string>("csv"), report_csv(report));
  if (log::level() >= log::Level::normal) fmt::print("{}: {}", input, format_report(report));
  return kOk;
}

}  // namespace metrica::cli
