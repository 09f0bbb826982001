// What the commands that adapt (adapt, pipeline) share: the metric at the
// input's vertices, and their progress output (a line per cycle, pass and
// round; the table of operators).
#pragma once

#include "cli.hpp"

#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/pipeline/adapter.hpp>

#include <optional>
#include <vector>

namespace metrica::cli {

// Per operator: items tried = applied + rejected + deferred, the
// candidates they weighed; on Speculative also conflicts (locks released,
// item replayed later), replays, the items left to one thread and, on
// several threads, the share of the parallel loops' thread time spent
// working (the rest is waiting at a loop's end for the last thread).
void print_operator_stats(const AdaptReport& r, bool serial, int threads);

// One line: the cycle's (pass's, round's) counts, its stages' applied and
// tried with their times, the share of edges in the unit band, the worst tet.
void print_cycle(const CycleReport& c);

// The metric at the mesh's vertices: the analytic metric evaluated there,
// or the file -m's values (the input's vertices), clamped to the size
// bounds and checked.
std::vector<Sym6> metric_at_vertices(const Options& o, const Mesh& mesh, const std::optional<AnalyticMetric>& analytic,
                                     const MetricBounds& bounds, std::size_t input_vertices);

}  // namespace metrica::cli
