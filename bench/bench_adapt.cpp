// End-to-end adaptation: output tets per second, the time share of each
// operator, and peak memory per output tet. The UGAWG `linear` metric on
// the unit cube with every size multiplied by `scale` (the tet count grows
// as scale^-3: 1 gives ~50k tets, 0.37 ~1M, 0.22 ~5M), one adaptation from
// the 4x4x4 cube, median of `runs`.
//
//   bench_adapt [scale=1] [runs=3] [space=log-euclidean] [precision=filtered]
#include "bench_common.hpp"

#include <metrica/allocator.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <fmt/core.h>

#include <string>
#include <thread>
#include <vector>

using namespace metrica;

int main(int argc, char** argv) {
  metrica::keep_freed_memory();  // allocator.hpp: pages reused from pass to pass
  const double scale = argc > 1 ? std::stod(argv[1]) : 1.0;
  const int runs = argc > 2 ? std::stoi(argv[2]) : 3;
  const PolicyChoice policies{argc > 3 ? argv[3] : "log-euclidean", argc > 4 ? argv[4] : "filtered", "serial"};
  check_policy_choice(policies);
  const MetricFunction metric = bench::scaled_linear_metric(scale);
  fmt::print("adapt: linear x {} on {} core(s), {} space, {} predicates, serial, median of {}\n", scale,
             std::thread::hardware_concurrency(), policies.space, policies.precision, runs);
  AdaptReport last;
  std::vector<CycleReport> cycles;  // of the last run
  std::size_t tets = 0;
  const double t = bench::median_seconds(runs, [&] {
    Mesh mesh = bench::start_mesh(metric);
    AdaptOptions o;
    AdaptInputs in{.metric = &metric};
    cycles.clear();
    in.on_cycle = [&](const CycleReport& c) { cycles.push_back(c); };
    last = adapt_by_name(mesh, o, policies, in);
    tets = mesh.num_tets();
  });
  const auto& c = last.cycles.back();
  fmt::print("output: {} vertices, {} tets; {:.2f} s (median); {:.0f} output tets/s\n", c.vertices, tets, t,
             static_cast<double>(tets) / t);
  fmt::print("quality: {:.2f}% of edges in range, min Q {:.3f}\n", 100.0 * c.conformity, c.min_quality);
  const double ops = last.ops.get("collapse").seconds + last.ops.get("split").seconds + last.ops.get("flip").seconds +
                     last.ops.get("smooth").seconds;
  fmt::print(
      "time share (last run, {:.2f} s): collapse {:.0f}%, split {:.0f}%, flips {:.0f}%, smoothing {:.0f}%, "
      "other (compaction, statistics) {:.0f}%\n",
      last.seconds, 100 * last.ops.get("collapse").seconds / last.seconds,
      100 * last.ops.get("split").seconds / last.seconds, 100 * last.ops.get("flip").seconds / last.seconds,
      100 * last.ops.get("smooth").seconds / last.seconds, 100 * (last.seconds - ops) / last.seconds);
  // Where the time goes, cycle by cycle (q: the quality phase).
  // Each operator: applied / tried.
  fmt::print(
      "cycle   vertices       tets         collapsed             split             flips          smoothed  in range  "
      "min Q  | "
      "seconds: collapse  split  flips  smooth  total\n");
  for (const auto& r : cycles)
    fmt::print(
        "{:>4}{} {:>10} {:>10} {:>8}/{:<8} {:>8}/{:<8} {:>8}/{:<8} {:>8}/{:<8} {:>8.2f}% {:>6.3f}  | {:>16.2f} "
        "{:>6.2f} {:>6.2f} "
        "{:>7.2f} {:>6.2f}\n",
        r.cycle, r.quality_phase ? 'q' : ' ', r.vertices, r.tets, r.ops.get("collapse").applied,
        r.ops.get("collapse").tried, r.ops.get("split").applied, r.ops.get("split").tried, r.ops.get("flip").applied,
        r.ops.get("flip").tried, r.ops.get("smooth").applied, r.ops.get("smooth").tried, 100.0 * r.conformity,
        r.min_quality, r.ops.get("collapse").seconds, r.ops.get("split").seconds, r.ops.get("flip").seconds,
        r.ops.get("smooth").seconds, r.seconds);
  fmt::print("peak memory {:.1f} MB, {:.0f} bytes per output tet\n", bench::peak_bytes() / 1e6,
             bench::peak_bytes() / static_cast<double>(tets));
  return 0;
}
