#include "cli.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/output_set.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/pipeline/adaptive_loop.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cmath>
#include <filesystem>

namespace metrica::cli {

int run_loop(const std::vector<std::string>& args) {
  Options o("loop", "--field NAME [-i START] [options]",
            "The adaptive loop with an analytic field in place of a solver (the verification study of\n"
            "the seed, section 5.2): each iteration evaluates the field at the vertices, builds the\n"
            "multiscale metric (L^p norm, target complexity, gradation), adapts the mesh, and measures\n"
            "the L2 norm of the P1 interpolation error on the adapted mesh (Grundmann-Moeller\n"
            "quadrature, degree 5). The complexity doubles every --double-every iterations. One line\n"
            "per iteration; --csv writes them as a table (iteration, complexity, vertices, tets,\n"
            "seconds, l2_error, transfer_error, conformity, min_q), --output-dir each mesh and metric.\n"
            "--quick: 6 iterations, complexity 1000 doubling every 3 (a minute on 2 cores).\n\n"
            "Examples:\n"
            "  metrica loop --field sinfun3 --quick --csv sinfun3.csv\n"
            "  metrica loop --field tanh3 --complexity 1000 --double-every 10 --iterations 80 --csv t.csv\n"
            "  metrica loop --field sinatan3 -i start.meshb --iterations 20 --output-dir run/");
  // The defaults shown and used are the library's.
  const LoopOptions d;
  o.input("start mesh (default: the 4x4x4 unit cube of the UGAWG)");
  o.add()("field", po::value<std::string>()->value_name("NAME"), "analytic field: sinfun3, tanh3, sinatan3")(
      "complexity", number_option(d.complexity)->value_name("C0"), "complexity of the first iteration")(
      "double-every", po::value<int>()->default_value(d.double_every)->value_name("K"), "iterations per complexity")(
      "iterations", po::value<int>()->default_value(d.iterations)->value_name("N"), "iterations in all")(
      "norm", number_option(d.norm)->value_name("P"), "L^p norm of the multiscale metric")(
      "gradation", number_option(d.gradation)->value_name("BETA"), "size gradation (0: none)")(
      "quick", "6 iterations at complexity 1000, doubling every 3 (for CI)");
  declare_setting(o, *adapt_setting("smooth-below"), d.adapt);
  o.add()("interpolate", "also transfer the previous field to each new mesh (a solver restart) and report its error")(
      "concurrency", po::value<std::string>()->default_value(d.concurrency)->value_name("C"),
      "speculative (--threads threads) or serial")(
      "output-dir", po::value<std::string>()->value_name("DIR"),
      "write each iteration's mesh and metric (loop-NN.meshb, loop-NN.solb)")(
      "geometry", po::value<std::string>()->value_name("MODEL"),
      "CAD model the start mesh's boundary lies on: new boundary vertices go on it (needs -i)");
  o.output_option("csv", "write one row per iteration", {});
  o.format_version("libMeshb version of the meshes and metrics --output-dir gets, 1-4 (default 2)");
  max_tets_option(o);
  if (!o.parse(args)) return kOk;
  if (!o.has("field")) throw UsageError("loop: give --field NAME (sinfun3, tanh3, sinatan3)");
  const AnalyticField field = *o.named("field", analytic_field_from_name);
  LoopOptions lo;
  lo.field = [field](const Point& p) { return evaluate(field, p); };
  lo.complexity = o.positive("complexity");
  lo.double_every = o.in_range("double-every", 1, 100000);
  lo.iterations = o.in_range("iterations", 1, 100000);
  lo.norm = o.in_range("norm", 1.0, 1e6);
  lo.gradation = o.in_range("gradation", 0.0, 1e6);
  lo.interpolate = o.has("interpolate");
  read_setting(o, *adapt_setting("smooth-below"), lo.adapt);
  lo.concurrency = o.get<std::string>("concurrency");
  if (!Concurrencies::contains(lo.concurrency))
    throw UsageError(fmt::format("loop: unknown concurrency '{}' ({})", lo.concurrency, Concurrencies::names()));
  if (o.has("quick")) {
    lo.iterations = 6;
    lo.double_every = 3;
    lo.complexity = 1000.0;
  }
  if (lo.gradation != 0 && !(lo.gradation >= 1)) throw UsageError("loop: --gradation must be >= 1 (or 0: none)");
  if (o.has("geometry") && !o.has("input")) throw UsageError("loop: --geometry needs the start mesh (-i)");
  // The last iteration's complexity bounds the run's size.
  const double last = loop_complexity(lo, lo.iterations - 1);
  const double predicted =
      check_predicted_size(o, last, fmt::format("the last iteration (iteration {})", lo.iterations));

  Mesh mesh;
  std::unique_ptr<CadModel> model;
  if (o.has("input")) {
    auto loaded = load_mesh(o.get<std::string>("input"), Valid::required, ridge_angle(o));
    mesh = std::move(loaded.mesh);
    if (o.has("geometry")) {
      model = open_geometry(o.get<std::string>("geometry"), mesh, &loaded.data, true);
      lo.model = model.get();
    }
  } else {
    mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  }
  if (o.dry_run()) {
    fmt::print(
        "loop: {} iterations from {} vertices; the last at complexity {:.4g}, about {:.3g} tets and {} of "
        "memory\n",
        lo.iterations, count_text(mesh.num_vertices()), last, predicted, bytes_text(predicted * kBytesPerTet));
    return kOk;
  }
  std::string dir;
  if (o.has("output-dir")) {
    dir = o.get<std::string>("output-dir");
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("loop: cannot create --output-dir {}: {}", dir, ec.message()));
    io::writable_target(dir + "/loop-01.meshb");
  }
  const bool talk = log::level() >= log::Level::normal;
  if (talk)
    fmt::print("loop: {} from {} vertices, complexity {} doubling every {}, {} iterations, p = {}, gradation {} ({})\n",
               to_string(field), count_text(mesh.num_vertices()), lo.complexity, lo.double_every, lo.iterations,
               lo.norm, lo.gradation,
               lo.concurrency == Serial::name ? std::string("serial") : fmt::format("{} threads", thread_count()));
  Stopwatch clock;
  lo.on_iteration = [&](const LoopRow& r, const Mesh& m) {
    if (talk) {
      fmt::print(
          "  {:>3}  complexity {:>8.0f}  {:>9} vertices {:>10} tets  L2 error {:.4e}{}  in range {:5.1f}%  "
          "min Q {:.3f}  {:.1f} s\n",
          r.iteration, r.complexity, count_text(r.vertices), count_text(r.tets), r.l2_error,
          r.transfer_error >= 0 ? fmt::format("  transfer {:.4e}", r.transfer_error) : "", 100 * r.conformity,
          r.min_quality, r.seconds);
      std::fflush(stdout);
    }
    if (!dir.empty()) {
      const std::string stem = fmt::format("{}/loop-{:02d}", dir, r.iteration);
      if (model) require_on_model(m, *model, fmt::format("loop: iteration {}", r.iteration));
      auto data = extract_mesh_data(m);
      if (model) complete_geometry_records(data, *model);
      io::write_mesh_file(stem + ".meshb", data, o.format_version());
      io::write_sol(stem + ".solb", metric_sol(m), o.format_version());
    }
  };
  const auto rows = adaptive_loop(mesh, lo);
  for (const auto& r : rows)
    if (!std::isfinite(r.l2_error) || !std::isfinite(r.min_quality))
      throw InputError(
          fmt::format("loop: iteration {} measured a non-finite error or quality; nothing written", r.iteration));
  if (const auto check = mesh.validate(); !check.ok())
    throw InputError(fmt::format("loop: the last mesh is invalid; nothing written\n{}", check.to_string()));
  if (o.has("csv")) io::write_file_atomically(o.get<std::string>("csv"), loop_csv(rows));
  if (model && talk) fmt::print("{}\n", model_distance_text(mesh, *model));
  if (talk) fmt::print("loop: {:.1f} s in all\n", clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
