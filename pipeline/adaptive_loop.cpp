#include <metrica/error.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/pipeline/adaptive_loop.hpp>
#include <metrica/point_location.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica {

double loop_complexity(const LoopOptions& o, int iteration) {
  const int doublings = o.double_every > 0 ? iteration / o.double_every : 0;
  return o.complexity * std::pow(2.0, doublings);
}

std::vector<LoopRow> adaptive_loop(Mesh& mesh, const LoopOptions& o) {
  if (!o.field) throw InputError("loop: no field");
  if (o.iterations < 1) throw InputError(fmt::format("loop: iterations must be >= 1 (got {})", o.iterations));
  if (!(o.complexity > 0)) throw InputError(fmt::format("loop: the complexity must be > 0 (got {})", o.complexity));
  if (!(o.norm >= 1)) throw InputError(fmt::format("loop: the norm p must be >= 1 (got {})", o.norm));
  std::vector<LoopRow> rows;
  // The field at the vertices of the current mesh: made once per mesh, it
  // measures one iteration's error and drives the next one's metric.
  std::vector<double> u = values_at_vertices(mesh, o.field);
  for (int it = 0; it < o.iterations; ++it) {
    Stopwatch clock;
    LoopRow row;
    row.iteration = it + 1;
    row.complexity = loop_complexity(o, it);
    MultiscaleOptions ms;
    ms.complexity = row.complexity;
    ms.norm = o.norm;
    ms.gradation = o.gradation > 0;
    if (ms.gradation) ms.gradation_options.beta = o.gradation;
    assign_metric(mesh, multiscale_metric(mesh, u, ms));
    Mesh previous;
    if (o.interpolate) previous = mesh;
    // This iteration's metric stays, on this mesh, the background of its
    // adaptation (docs/architecture.md).
    const BackgroundMetric background(mesh);
    const AdaptReport report =
        adapt_by_name(mesh, o.adapt, {.concurrency = o.concurrency}, {.background = &background, .model = o.model});
    row.seconds = clock.seconds();
    row.vertices = mesh.num_vertices();
    row.tets = mesh.num_tets();
    if (!report.cycles.empty()) {
      row.conformity = report.cycles.back().conformity;
      row.min_quality = report.cycles.back().min_quality;
    }
    std::vector<double> adapted = values_at_vertices(mesh, o.field);
    row.l2_error = l2_interpolation_error(mesh, adapted, o.field);
    if (o.interpolate)
      row.transfer_error = l2_interpolation_error(mesh, interpolate_vertex_field(previous, u, mesh), o.field);
    u = std::move(adapted);
    rows.push_back(row);
    if (o.on_iteration) o.on_iteration(row, mesh);
  }
  return rows;
}

std::string loop_csv(const std::vector<LoopRow>& rows) {
  std::string csv = "iteration,complexity,vertices,tets,seconds,l2_error,transfer_error,conformity,min_q\n";
  for (const auto& r : rows)
    csv += fmt::format("{},{:.0f},{},{},{:.3f},{:.6e},{:.6e},{:.5f},{:.5f}\n", r.iteration, r.complexity, r.vertices,
                       r.tets, r.seconds, r.l2_error, r.transfer_error, r.conformity, r.min_quality);
  return csv;
}

}  // namespace metrica
