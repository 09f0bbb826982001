#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/interpolation_error.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/point_location.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <cmath>
#include <optional>

namespace metrica::cli {

namespace {

// The field at a mesh's vertices: from the file of option `file_option`
// when given, else the analytic field there.
std::vector<double> field_on(const LoadedMesh& m, const Options& o, const char* file_option,
                             const std::optional<AnalyticField>& analytic) {
  if (o.has(file_option)) {
    const auto path = o.get<std::string>(file_option);
    return scalar_field_from_sol(io::read_sol(path), m.data.vertices.size(), path);
  }
  return values_at_vertices(m.mesh, [f = *analytic](const Point& p) { return evaluate(f, p); });
}

}  // namespace

int run_error(const std::vector<std::string>& args) {
  Options o("error", "[-i] MESH (--analytic NAME | --field F.solb) [--truth FINE.meshb [--truth-field T.solb]]",
            "The L2 norm of the error of a P1 field on a mesh (the measure of the verification study,\n"
            "seed section 5.2):\n"
            "  against an analytic field (--analytic; the mesh's values are that field at its vertices\n"
            "  unless --field gives them): exact integration of (u - u_h)^2, Grundmann-Moeller degree 5;\n"
            "  against a finer mesh's solution (--truth): the field is transferred to the truth mesh's\n"
            "  vertices (point location, P1) and its difference from the truth field (--truth-field, or\n"
            "  the analytic field at the truth's vertices) integrated there - the measure of refine's\n"
            "  error-estimation results, where the truth is the last mesh of the loop.\n"
            "Prints the vertex count, h = vertices^(-1/3) and the error on one line.\n\n"
            "Examples:\n"
            "  metrica error loop-40.meshb --analytic tanh3\n"
            "  metrica error loop-40.meshb --analytic tanh3 --truth loop-80.meshb\n"
            "  metrica error coarse.meshb --field coarse.solb --truth fine.meshb --truth-field fine.solb");
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.add()("analytic", po::value<std::string>()->value_name("NAME"), "analytic field: sinfun3, tanh3, sinatan3")(
      "field", po::value<std::string>()->value_name("FILE"), "the field at the mesh's vertices (.sol, .solb)")(
      "truth", po::value<std::string>()->value_name("MESH"), "a finer mesh whose solution is the reference")(
      "truth-field", po::value<std::string>()->value_name("FILE"), "the field at the truth mesh's vertices");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the mesh (-i)");
  const auto analytic = o.named("analytic", analytic_field_from_name);
  if (!analytic && !o.has("field")) throw UsageError("metrica error: give --analytic NAME or --field F.solb");
  if (!o.has("truth") && !analytic)
    throw UsageError("metrica error: without --truth the reference is an analytic field: give --analytic NAME");
  if (o.has("truth") && !analytic && !o.has("truth-field"))
    throw UsageError("metrica error: give the truth mesh's field (--truth-field) or an analytic field (--analytic)");
  if (o.has("truth-field") && !o.has("truth")) throw UsageError("metrica error: --truth-field needs --truth MESH");

  Stopwatch clock;
  const auto mesh = load_mesh(input);
  const auto values = field_on(mesh, o, "field", analytic);
  if (o.dry_run()) return kOk;
  double error = 0;
  std::string against;
  if (o.has("truth")) {
    const auto truth_path = o.get<std::string>("truth");
    const auto truth = load_mesh(truth_path);
    const auto reference = field_on(truth, o, "truth-field", analytic);
    std::size_t outside = 0;
    const auto transferred = interpolate_vertex_field(mesh.mesh, values, truth.mesh, &outside);
    error = l2_difference(truth.mesh, transferred, reference);
    against = fmt::format("against {} ({} vertices", truth_path, count_text(truth.mesh.num_vertices()));
    if (outside > 0) against += fmt::format(", {} outside the mesh, clamped", count_text(outside));
    against += ")";
  } else {
    error = l2_interpolation_error(mesh.mesh, values, [&](const Point& p) { return evaluate(*analytic, p); });
    against = fmt::format("against the exact {}", to_string(*analytic));
  }
  if (!std::isfinite(error)) throw InputError(fmt::format("error: the L2 error of {} is not finite", input));
  const std::size_t n = mesh.mesh.num_vertices();
  if (log::level() >= log::Level::normal)
    fmt::print("{}: vertices {}  h {:.6e}  L2 error {:.6e}  {}  {:.2f} s\n", input, n,
               std::pow(static_cast<double>(n), -1.0 / 3.0), error, against, clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
