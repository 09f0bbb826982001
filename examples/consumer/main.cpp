// Adapts a box to the UGAWG linear metric with a pipeline of our own
// (split before collapse, edge-weight flips) on an installed Metrica.
#include <metrica/box.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

using namespace metrica;
using A = Adapter<LogEuclidean, Serial>;

int main() {
  Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  const MetricFunction linear = [](const Point& p) { return evaluate(AnalyticMetric::linear, p); };
  assign_metric(mesh, linear);
  A adapter(mesh, &linear);
  Pipeline<A> p = standard_pipeline<A>(AdaptOptions{});
  p.cycle = {{"split", [](A& a) { return a.split({}); }},
             {"collapse", [](A& a) { return a.collapse({}); }},
             {"edge-weight", [](A& a) { return a.flips<MaxMinEdgeWeight>({}); }},
             {"smooth", [](A& a) { return a.smooth({.below = 0.3}); }}};
  const AdaptReport& r = run_pipeline(adapter, p);
  const bool ok = mesh.validate().ok();
  fmt::print("{} tets, {:.1f}% of edges in range, min Q {:.3f}: {}\n", mesh.num_tets(),
             100 * r.cycles.back().conformity, r.cycles.back().min_quality, ok ? "valid" : "INVALID");
  return ok ? 0 : 1;
}
