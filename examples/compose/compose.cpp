// A custom pipeline on Adapter (policies bound once): a box adapted to UGAWG polar-2 with the seed's
// reconnection (metric Delaunay, then max-min edge-weight flips each cycle; the standard quality
// phase), each pass incremental under its stage's name. Swap a policy, a criterion or a stage and compare.
//   build/examples/compose/compose_pipeline [cycles]
#include <metrica/box.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cstdlib>

using namespace metrica;
using A = Adapter<LogEuclidean, Serial>;

int main(int argc, char** argv) {
  Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  const MetricFunction polar2 = [](const Point& p) { return evaluate(AnalyticMetric::polar2, p); };
  assign_metric(mesh, polar2);
  A adapter(mesh, &polar2);
  adapter.on_cycle = [](const CycleReport& c) { fmt::print("{} tets, min Q {:.3f}\n", c.tets, c.min_quality); };
  Pipeline<A> p = standard_pipeline<A>(AdaptOptions{});
  p.max_cycles = argc > 1 ? std::atoi(argv[1]) : 8;
  p.cycle = {{"collapse", [](A& a) { return a.collapse({}); }},
             {"split", [](A& a) { return a.split({}); }},
             {"delaunay", [](A& a) { return a.flips<MetricDelaunay<>>({}); }},
             {"edge-weight", [](A& a) { return a.flips<MaxMinEdgeWeight>({}); }},
             {"smooth", [](A& a) { return a.smooth({.below = 0.3}); }}};
  run_pipeline(adapter, p);
  const auto check = mesh.validate();
  fmt::print("{}\n{}", check.ok() ? "valid" : check.to_string(), format_report(quality_report(mesh)));
  return check.ok() ? 0 : 1;
}
