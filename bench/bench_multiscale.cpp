// Run time of the multiscale metric on a box mesh: Hessian recovery,
// normalisation, bounds and gradation, for each analytic field.
//
//   build/bench/bench_multiscale [hexes-per-direction=55] [complexity=100000] [runs=3]
//
// 55^3 hexes x 6 = 998,250 tets.
#include "bench_common.hpp"

#include <metrica/box.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/policies/threads.hpp>

#include <fmt/core.h>

#include <string>

int main(int argc, char** argv) {
  using namespace metrica;
  const int n = argc > 1 ? std::stoi(argv[1]) : 55;
  const double target = argc > 2 ? std::stod(argv[2]) : 100000.0;
  const int runs = argc > 3 ? std::stoi(argv[3]) : 3;
  const Mesh mesh = make_box({.nx = n, .ny = n, .nz = n});
  std::vector<Point> pts(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) pts[v] = mesh.point(v);
  fmt::print(
      "multiscale metric on a {}^3 box ({} tets, {} vertices), complexity {}, p = 2, mixed gradation 3,\n"
      "median of {} runs, {} cores\n\n",
      n, mesh.num_tets(), mesh.num_vertices(), target, runs, core_count());
  fmt::print("{:<10} {:>10} {:>12} {:>12} {:>12} {:>12}\n", "field", "total s", "Hessian s", "gradation s",
             "relaxations", "complexity");
  for (const auto f : {AnalyticField::sinfun3, AnalyticField::tanh3, AnalyticField::sinatan3}) {
    const auto values = analytic_field_values(f, pts);
    MultiscaleOptions o;
    o.complexity = target;
    o.gradation_options.beta = 3.0;
    MultiscaleReport last;
    std::vector<MultiscaleReport> reports;
    const double t = bench::median_seconds(runs, [&] {
      multiscale_metric(mesh, values, o, &last);
      reports.push_back(last);
    });
    fmt::print("{:<10} {:>10.3f} {:>12.3f} {:>12.3f} {:>12} {:>12.6g}\n", to_string(f), t, last.hessian_seconds,
               last.gradation_seconds, last.relaxations, last.complexity);
  }
  return 0;
}
