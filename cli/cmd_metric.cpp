#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/curvature_metric.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/intersection.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <numbers>
#include <optional>

namespace metrica::cli {

namespace {

// The command's options; the multiscale defaults shown and used are the
// library's (MultiscaleOptions{}).
void declare_options(Options& o) {
  const MultiscaleOptions d;
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.output("metric (.sol, .solb)", {io::FileFormat::sol, io::FileFormat::solb});
  max_tets_option(o);
  o.format_version("libMeshb version to write (default: the mesh's)");
  o.add()("analytic", po::value<std::string>()->value_name("NAME"), "analytic metric: linear, polar-1, polar-2")(
      "field", po::value<std::string>()->value_name("NAME"), "analytic field for a multiscale metric")(
      "field-file", po::value<std::string>()->value_name("FILE"), "solution (.sol/.solb) for a multiscale metric")(
      "fields", po::value<std::string>()->value_name("LIST"),
      "fields of --field-file, intersected: K (field K, 1-based; a vector: all its components), "
      "K.x K.y K.z (one component), all; comma-separated (default: the first scalar field)")(
      "metric,m", po::value<std::string>()->value_name("FILE"), "an existing metric to post-process")(
      "complexity", po::value<double>()->value_name("C"),
      fmt::format("target complexity (multiscale default {})", d.complexity).c_str())(
      "norm", number_option(d.norm)->value_name("P"), "L^p norm of the multiscale metric (p >= 1)")(
      "gradation", po::value<double>()->value_name("BETA"), "size gradation (>= 1; none when not given)")(
      "gradation-space", po::value<std::string>()->default_value("mixed")->value_name("S"),
      "gradation space: mixed (Alauzet 2010, t = 1/8) or metric")(
      "hmin", po::value<double>()->value_name("H"), "smallest size")("hmax", po::value<double>()->value_name("H"),
                                                                     "largest size")(
      "max-anisotropy", po::value<double>()->value_name("R"), "largest ratio of sizes of one tensor")(
      "intersect", po::value<std::string>()->value_name("FILE"), "intersect with this metric (.sol/.solb)")(
      "geometry", po::value<std::string>()->value_name("MODEL"),
      "CAD model of the mesh's boundary: its curvatures bound the sizes (.step .iges .brep .geo)")(
      "curvature-angle", po::value<double>()->default_value(8.0)->value_name("DEG"),
      "with --geometry: the largest turn of the facets between neighbouring vertices, in degrees");
}

// The scalar fields of a multiscale metric at the mesh's vertices: the
// analytic field, or the chosen fields of --field-file; `what` says which.
std::vector<std::vector<double>> field_values(const Options& o, const std::vector<Point>& vertices,
                                              const std::optional<AnalyticField>& analytic, std::string& what) {
  std::vector<std::vector<double>> values;
  if (analytic) {
    values.push_back(analytic_field_values(*analytic, vertices));
    what = fmt::format("multiscale metric of {}", to_string(*analytic));
    return values;
  }
  const auto path = o.get<std::string>("field-file");
  auto chosen =
      select_fields(io::read_sol(path), vertices.size(), o.has("fields") ? o.get<std::string>("fields") : "", path);
  std::string names;
  for (auto& f : chosen) {
    names += (names.empty() ? "" : ", ") + f.name;
    values.push_back(std::move(f.values));
  }
  what = o.has("fields") ? fmt::format("multiscale metric of {} (fields {}, intersected)", path, names)
                         : fmt::format("multiscale metric of {}", path);
  return values;
}

// The multiscale metric of `values` (one field, or several intersected).
std::vector<Sym6> multiscale_field(const Options& o, const Mesh& mesh, const std::vector<std::vector<double>>& values,
                                   const MetricBounds& bounds, const GradationOptions& grading, double norm) {
  MultiscaleOptions ms;
  if (o.has("complexity")) ms.complexity = o.get<double>("complexity");
  ms.norm = norm;
  ms.bounds = bounds;
  ms.gradation = o.has("gradation");
  ms.gradation_options = grading;
  MultiscaleReport rep;
  auto field = values.size() == 1 ? multiscale_metric(mesh, values.front(), ms, &rep)
                                  : multiscale_metric(mesh, values, ms, &rep);
  log::info("multiscale: Hessian {:.3f} s, gradation {:.3f} s, {} relaxations, total {:.3f} s", rep.hessian_seconds,
            rep.gradation_seconds, rep.relaxations, rep.total_seconds);
  return field;
}

// A metric given as such: analytic, or read from -m; `what` says which.
std::vector<Sym6> given_field(const Options& o, const std::vector<Point>& vertices,
                              const std::optional<AnalyticMetric>& analytic, std::string& what) {
  if (analytic) {
    what = fmt::format("metric '{}'", to_string(*analytic));
    return analytic_metric_field(*analytic, vertices);
  }
  const auto path = o.get<std::string>("metric");
  what = fmt::format("metric of {}", path);
  return metric_field_from_sol(io::read_sol(path), vertices.size(), path);
}

// A given metric scaled to --complexity, bounded, graded (and scaled
// again).
void scale_bound_grade(const Options& o, const Mesh& mesh, std::vector<Sym6>& field, const MetricBounds& bounds,
                       const GradationOptions& grading) {
  const auto dual = dual_volumes(mesh);
  if (o.has("complexity")) scale_to_complexity(field, dual, o.get<double>("complexity"));
  clamp_metrics(field, bounds);
  if (o.has("gradation")) {
    limit_gradation(mesh, field, grading);
    if (o.has("complexity")) scale_to_complexity(field, dual, o.get<double>("complexity"));
  }
}

}  // namespace

int run_metric(const std::vector<std::string>& args) {
  Options o("metric", "[-i] MESH (--analytic NAME | --field NAME | --field-file F.solb | -m M.solb) [-o] OUTPUT",
            "Writes a metric field (one symmetric tensor per vertex, SolAtVertices) for a mesh, from one of:\n"
            "  --analytic NAME    a UGAWG analytic metric: linear, polar-1, polar-2;\n"
            "  --field NAME       the multiscale metric of an analytic field: sinfun3, tanh3, sinatan3;\n"
            "  --field-file F     the multiscale metric of a solution (.sol/.solb): its first scalar field,\n"
            "                     or the fields --fields chooses, each scaled to the complexity, intersected;\n"
            "  -m M               an existing metric (to scale, bound, grade or intersect).\n"
            "The multiscale metric (Loseille & Alauzet) controls the L^p norm of the P1 interpolation error\n"
            "for a target complexity (--complexity, default 1000); its Hessian comes from L2-projection\n"
            "recovery, replaced at boundary vertices by the mean of their interior neighbours'. For the other sources "
            "--complexity scales the field to that complexity.\n"
            "Then, in order: bounds (--hmin, --hmax, --max-anisotropy), gradation (--gradation, mixed space\n"
            "by default) with rescaling to the complexity, and intersection with --intersect.\n"
            "With --geometry MODEL the curved boundaries of the CAD model bound the sizes last, whatever\n"
            "the complexity: along each principal direction of curvature k of the surfaces around a\n"
            "boundary vertex, h <= --curvature-angle / |k| (the facets turn by at most that angle), graded\n"
            "into the volume by --gradation when given.\n"
            "The output is .solb or .sol (libMeshb version of the mesh unless --format-version).\n\n"
            "Examples:\n"
            "  metrica metric cube-linear-00.meshb --analytic linear -o linear.solb\n"
            "  metrica metric cube.meshb --field sinfun3 --complexity 8000 --gradation 3 -o m.solb\n"
            "  metrica metric flow.meshb --field-file flow.sol --fields 1,2 --complexity 20000 -o m.solb\n"
            "  metrica metric flow.meshb --field-file flow.sol --fields 1,2 --geometry channel.geo -o m.solb");
  declare_options(o);
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  const auto output = o.required("output", "the output metric (-o)");
  o.one_of({"analytic", "field", "field-file", "metric"},
           "exactly one source: --analytic, --field, --field-file or -m");
  if (o.has("fields") && !o.has("field-file")) throw UsageError("metric: --fields chooses among --field-file's fields");
  // The form of the list before any file is read (which fields exist is
  // the file's to say).
  if (o.has("fields")) o.as_usage([&] { return parse_field_selection(o.get<std::string>("fields")); });

  MetricBounds bounds = o.size_bounds();
  if (o.has("max-anisotropy")) bounds.max_anisotropy = o.in_range("max-anisotropy", 1.0, 1e300);
  GradationOptions grading;
  grading.space = *o.named("gradation-space", gradation_space_from_name);
  const auto analytic_field = o.named("field", analytic_field_from_name);
  const auto analytic_metric = o.named("analytic", analytic_metric_from_name);
  if (o.has("gradation")) grading.beta = o.in_range("gradation", 1.0, 1e6);
  const double norm = o.in_range("norm", 1.0, 1e6);
  if (o.has("complexity")) o.positive("complexity");
  const double curvature_angle = o.in_range("curvature-angle", 0.1, 90.0) * std::numbers::pi / 180.0;
  if (!o.vm()["curvature-angle"].defaulted() && !o.has("geometry"))
    throw UsageError("metric: --curvature-angle bounds the sizes on a CAD model's curved boundary: give --geometry");

  Stopwatch clock;
  auto loaded = load_mesh(input, Valid::required, ridge_angle(o));
  Mesh& mesh = loaded.mesh;
  std::unique_ptr<CadModel> model;
  if (o.has("geometry")) model = open_geometry(o.get<std::string>("geometry"), mesh, &loaded.data);
  const std::size_t n = loaded.data.vertices.size();
  if (o.has("complexity")) check_predicted_size(o, o.get<double>("complexity"), "the target (--complexity)");

  std::vector<Sym6> field;
  std::string what;
  if (o.has("field") || o.has("field-file")) {
    auto values = field_values(o, loaded.data.vertices, analytic_field, what);
    if (o.dry_run()) return kOk;
    field = multiscale_field(o, mesh, values, bounds, grading, norm);
  } else {
    field = given_field(o, loaded.data.vertices, analytic_metric, what);
    if (o.dry_run()) return kOk;
    scale_bound_grade(o, mesh, field, bounds, grading);
  }
  if (model) {
    const auto bound = curvature_metric(mesh, *model, curvature_angle);
    for (std::size_t v = 0; v < n; ++v) field[v] = intersect(field[v], bound[v]);
    if (o.has("gradation")) limit_gradation(mesh, field, grading);
    what += fmt::format(", curved boundaries of {} at {:g} degrees", o.get<std::string>("geometry"),
                        o.get<double>("curvature-angle"));
  }
  if (o.has("intersect")) {
    const auto path = o.get<std::string>("intersect");
    const auto other = metric_field_from_sol(io::read_sol(path), n, path);
    for (std::size_t v = 0; v < n; ++v) field[v] = intersect(field[v], other[v]);
    what += fmt::format(" intersected with {}", path);
  }
  check_metric_field(field, what);
  check_predicted_size(o, complexity(mesh, field), "the metric");
  auto sol = metric_field_to_sol(field);
  sol.version = loaded.data.version;
  io::write_sol(output, sol, o.format_version(), sweep_runner(sol.count));
  if (log::level() >= log::Level::normal)
    fmt::print("wrote {}: {} at {} vertices, complexity {:.6g} ({:.2f} s)\n", output, what, count_text(n),
               complexity(mesh, field), clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
