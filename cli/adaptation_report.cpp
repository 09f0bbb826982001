#include "adaptation_report.hpp"

#include <metrica/io/meshb.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>

namespace metrica::cli {

namespace {

std::string stats_text(const char* name, const OperatorStats& s) {
  const std::string conflicts = s.conflicts > 0 ? fmt::format(", {} conflicts", count_text(s.conflicts)) : "";
  return fmt::format("{} {}/{} ({:.2f} s{})", name, count_text(s.applied), count_text(s.tried), s.seconds, conflicts);
}

}  // namespace

void print_operator_stats(const AdaptReport& r, bool serial, int threads) {
  for (const auto& [name, s] : r.ops) {
    std::string text = fmt::format(
        "  {:<8} tried {:>10} applied {:>10} rejected {:>10} deferred {:>6} "
        "candidates {:>10}",
        name, count_text(s.tried), count_text(s.applied), count_text(s.rejected), count_text(s.deferred),
        count_text(s.candidates));
    if (!serial) {
      const std::string busy = threads > 1 && s.thread_seconds > 0.0
                                   ? fmt::format(" busy {:.1f}%", 100.0 * s.busy_seconds / s.thread_seconds)
                                   : "";
      text += fmt::format(" conflicts {:>8} ({:.2f}%) replays {:>8} one-thread tail {:>6}{}", count_text(s.conflicts),
                          s.tried > 0 ? 100.0 * double(s.conflicts) / double(s.tried + s.conflicts) : 0.0,
                          count_text(s.replays), count_text(s.serial_tail), busy);
    }
    // Of the pass's time, what ran outside the policy's loops over its
    // items: the candidates gathered and ordered, the scratch set up
    // (sweeps of their own, parallel or not).
    fmt::print("{} | {:.2f} s, outside loops {:.2f} s\n", text, s.seconds, std::max(0.0, s.seconds - s.loop_seconds));
  }
  // Where the adaptation's time went: the operators' passes (in their
  // loops, parallel under a speculative policy; outside them, each pass's
  // set-up), the cycles' ends (compaction, the heap handed back, the
  // measures) and the rest (the stages' own steps between passes).
  double passes = 0, loops = 0;
  for (const auto& [name, s] : r.ops) {
    passes += s.seconds;
    loops += std::min(s.loop_seconds, s.seconds);
  }
  const double closing = r.closing_seconds();
  fmt::print(
      "  time: passes {:.2f} s (in their loops {:.2f} s, outside {:.2f} s), cycle ends (compaction, measures) "
      "{:.2f} s, the rest {:.2f} s, of {:.2f} s\n",
      passes, loops, passes - loops, closing, std::max(0.0, r.seconds - passes - closing), r.seconds);
}

void print_cycle(const CycleReport& c) {
  std::string ops;
  // A stage with nothing to try (a swap without internal surfaces or a
  // model, a projection with every vertex on the model) is left out.
  for (const auto& [name, s] : c.ops)
    if (s.tried > 0 || s.candidates > 0) ops += " | " + stats_text(name.c_str(), s);
  // A quality pass before the phase's last does not measure the share in
  // range (CycleReport::conformity_measured).
  const std::string in_range = c.conformity_measured ? fmt::format("{:5.1f}%", 100.0 * c.conformity) : "    - ";
  fmt::print("  {} {:>2}: {:>9} vertices {:>10} tets{} | in range {} min Q {:.3f} | {:.2f} s\n",
             c.repair          ? "repair"
             : c.quality_phase ? "polish"
                               : "cycle ",
             c.cycle, count_text(c.vertices), count_text(c.tets), ops, in_range, c.min_quality, c.seconds);
  std::fflush(stdout);
}

std::vector<Sym6> metric_at_vertices(const Options& o, const Mesh& mesh, const std::optional<AnalyticMetric>& analytic,
                                     const MetricBounds& bounds, std::size_t input_vertices) {
  std::vector<Sym6> field;
  if (analytic) {
    std::vector<Point> points(mesh.vertex_capacity(), Point::Zero());
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      if (mesh.vertex_alive(v)) points[v] = mesh.point(v);
    field = analytic_metric_field(*analytic, points);
  } else {
    const auto path = o.get<std::string>("metric");
    field = metric_field_from_sol(io::read_sol(path), input_vertices, path);
  }
  clamp_metrics(field, bounds);
  const std::string source = analytic ? fmt::format("metric '{}'", to_string(*analytic)) : o.get<std::string>("metric");
  check_metric_field(field, source);
  return field;
}

}  // namespace metrica::cli
