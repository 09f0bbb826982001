// A researcher's starting point: a pipeline composed by hand from the
// operators, with the policies chosen at compile time.
//
// It adapts a box to the UGAWG polar-2 metric with the seed's reconnection
// (metric Delaunay flips while refining, then max-min edge-weight flips,
// then quality flips), and prints what each step did. Swap a policy (say
// Isotropic for LogEuclidean, Exact for Filtered) or an operator and
// compare.
//
//   build/examples/compose/compose_pipeline [cycles]
#include <metrica/box.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/operators/adapt.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cstdlib>

using namespace metrica;

using Space = LogEuclidean;
using Exactness = Filtered;
using Threads = Serial;

namespace {
void step(const char* what, const OperatorStats& s, const Mesh& mesh) {
  double min_q = 0.0;
  const double in_range = conformity<Space>(mesh, &min_q);
  fmt::print("  {:<28} applied {:>7} of {:>8} ({:.2f} s) -> {:>7} tets, {:5.1f}% in range, min Q {:.3f}\n", what,
             s.applied, s.tried, s.seconds, mesh.num_tets(), 100.0 * in_range, min_q);
}
}  // namespace

int main(int argc, char** argv) {
  const int cycles = argc > 1 ? std::atoi(argv[1]) : 8;
  Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  const MetricFunction metric = [](const Point& p) { return evaluate(AnalyticMetric::polar2, p); };
  std::vector<Sym6> field(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) field[v] = metric(mesh.point(v));
  assign_metric(mesh, field);

  RefineOptions refine;
  refine.metric = &metric;  // new vertices take the exact metric
  CollapseOptions collapse;
  collapse.metric = &metric;
  SmoothOptions smooth;
  smooth.metric = &metric;
  smooth.below = 0.3;
  ReconnectOptions flips;

  for (int c = 0; c < cycles; ++c) {
    fmt::print("cycle {}\n", c);
    step("collapse", collapse_edges<Space, Exactness, Threads>(mesh, collapse), mesh);
    step("split", refine_edges<Space, Exactness, Threads>(mesh, refine), mesh);
    step("flips (metric Delaunay)", reconnect<Space, Exactness, Threads, MetricDelaunay>(mesh, flips), mesh);
    step("flips (max-min edge weight)", reconnect<Space, Exactness, Threads, MaxMinEdgeWeight>(mesh, flips), mesh);
    step("smooth", smooth_vertices<Space, Exactness, Threads>(mesh, smooth), mesh);
    mesh.compact();
  }
  fmt::print("quality phase\n");
  smooth.below = 1.0;
  for (int pass = 0; pass < 3; ++pass) {
    step("flips (mean ratio)", reconnect<Space, Exactness, Threads, MinQuality>(mesh, flips), mesh);
    step("smooth", smooth_vertices<Space, Exactness, Threads>(mesh, smooth), mesh);
  }
  const auto check = mesh.validate();
  fmt::print("{}\n{}", check.ok() ? "valid" : check.to_string(), format_report(quality_report(mesh)));
  return check.ok() ? 0 : 1;
}
