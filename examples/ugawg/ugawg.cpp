// The UGAWG loop on the unit cube: adapt to an analytic metric, evaluate
// the metric on the new mesh, adapt again, N times (UGAWG, "Unstructured
// Grid Adaptation Working Group" benchmark cases linear, polar-1, polar-2).
// One table row per iteration; a CSV with --csv.
//
//   build/examples/ugawg/ugawg [--iterations N] [--csv FILE] [--space S] [--points RULE] [CASE...]
//   CASE: linear, polar-1, polar-2 (default: all three)
#include <metrica/allocator.hpp>
#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace metrica;

namespace {
// Peak resident memory of this process so far (VmHWM), in MB.
double peak_mb() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return 0.0;
  char line[256];
  double kb = 0.0;
  while (std::fgets(line, sizeof line, f) != nullptr)
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atof(line + 6);
  std::fclose(f);
  return kb / 1024.0;
}
}  // namespace

int main(int argc, char** argv) try {
  metrica::keep_freed_memory();  // allocator.hpp: pages reused from pass to pass
  int iterations = 8;
  std::string csv_path, space_name = "log-euclidean", points = "edge", concurrency = "serial";
  std::vector<std::string> cases;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--iterations" && i + 1 < argc)
      iterations = std::stoi(argv[++i]);
    else if (a == "--csv" && i + 1 < argc)
      csv_path = argv[++i];
    else if (a == "--space" && i + 1 < argc)
      space_name = argv[++i];
    else if (a == "--points" && i + 1 < argc)
      points = argv[++i];
    else if (a == "--concurrency" && i + 1 < argc)
      concurrency = argv[++i];
    else if (a == "--threads" && i + 1 < argc)
      set_thread_count(std::stoi(argv[++i]));
    else if (a == "-h" || a == "--help") {
      fmt::print(
          "usage: ugawg [--iterations N] [--csv FILE] [--space S] [--points edge|centroid]\n"
          "             [--concurrency serial|speculative] [--threads N] [linear polar-1 polar-2]\n"
          "(serial by default: the figures of the README are reproducible to the bit)\n");
      return 0;
    } else
      cases.push_back(a);
  }
  if (cases.empty()) cases = {"linear", "polar-1", "polar-2"};
  const PolicyChoice policies{space_name, Precisions::at<0>::name.data(), concurrency};
  check_policy_choice(policies);
  const PointRule rule = point_rule_from_name(points);
  std::string csv = "case,iteration,vertices,tets,seconds,conformity,min_q,mean_q,vertices_per_complexity,peak_mb\n";
  for (const auto& name : cases) {
    const AnalyticMetric kind = analytic_metric_from_name(name);
    const MetricFunction metric = [kind](const Point& p) { return evaluate(kind, p); };
    Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});  // the UGAWG start mesh, cube-linear-00
    fmt::print("{}\n  {:>4} {:>9} {:>10} {:>8} {:>9} {:>7} {:>7} {:>8} {:>8}\n", name, "iter", "vertices", "tets",
               "seconds", "in range", "min Q", "mean Q", "N/C", "peak MB");
    for (int it = 1; it <= iterations; ++it) {
      std::vector<Sym6> field(mesh.vertex_capacity(), isotropic_metric(1.0));
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
        if (mesh.vertex_alive(v)) field[v] = metric(mesh.point(v));
      assign_metric(mesh, field);
      AdaptOptions o;
      o.points = rule;
      Stopwatch clock;
      adapt_by_name(mesh, o, policies, {.metric = &metric});
      const double seconds = clock.seconds();
      const auto r = quality_report(mesh, policies.space);
      fmt::print("  {:>4} {:>9} {:>10} {:>8.2f} {:>8.2f}% {:>7.3f} {:>7.3f} {:>8.3f} {:>8.1f}\n", it, r.vertices,
                 r.tets, seconds, 100.0 * r.unit_length_share, r.quality.min, r.quality.mean, r.vertices_per_complexity,
                 peak_mb());
      std::fflush(stdout);
      csv +=
          fmt::format("{},{},{},{},{:.3f},{:.5f},{:.5f},{:.5f},{:.4f},{:.1f}\n", name, it, r.vertices, r.tets, seconds,
                      r.unit_length_share, r.quality.min, r.quality.mean, r.vertices_per_complexity, peak_mb());
    }
  }
  if (!csv_path.empty()) io::write_file_atomically(csv_path, csv);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
