#include "cli.hpp"

#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

namespace metrica::cli {

int run_metric(const std::vector<std::string>& args) {
  Options o("metric", "[-i] MESH --analytic NAME [-o] OUTPUT",
            "Writes a metric field (one symmetric tensor per vertex, SolAtVertices) for a mesh. For now from\n"
            "an analytic metric of the UGAWG benchmarks: linear, polar-1, polar-2. The output is .solb or\n"
            ".sol (libMeshb version of the mesh unless --format-version).\n\n"
            "Example: metrica metric cube-linear-00.meshb --analytic linear -o linear.solb");
  o.input("mesh (.mesh, .meshb)");
  o.output("metric (.sol, .solb)");
  o.format_version("libMeshb version to write (default: the mesh's)");
  o.add()("analytic", po::value<std::string>()->value_name("NAME"), "analytic metric: linear, polar-1, polar-2");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  const auto output = o.required("output", "the output metric (-o)");
  const auto name = o.required("analytic", "the metric (--analytic NAME)");
  const auto kind = analytic_metric_from_name(name);

  Stopwatch clock;
  const auto loaded = load_mesh(input);
  const auto field = analytic_metric_field(kind, loaded.data.vertices);
  check_metric_field(field, name);
  auto sol = metric_field_to_sol(field);
  sol.version = loaded.data.version;
  io::write_sol(output, sol, o.format_version());
  if (log::level() >= log::Level::normal)
    fmt::print("wrote {}: metric '{}' at {} vertices ({:.2f} s)\n", output, name, count_text(field.size()),
               clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
