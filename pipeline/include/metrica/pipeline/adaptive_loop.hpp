// The adaptive loop with an analytic field in place of a flow solver (the
// verification study of the seed, section 5.2, and of the UGAWG
// error-estimation results): each iteration evaluates the field at the
// vertices, builds the multiscale metric (Lp norm, target complexity,
// gradation), adapts the mesh to it, and measures the L2 norm of the P1
// interpolation error of the field on the adapted mesh. The complexity
// starts at `complexity` and doubles every `double_every` iterations, so
// the error can be plotted against the vertex count (second order: error
// ~ N^(-2/3)).
#pragma once

#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/interpolation_error.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <functional>
#include <string>
#include <vector>

namespace metrica {

struct LoopOptions {
  ScalarFunction field;        // the "solution" (analytic)
  double complexity = 1000.0;  // of the first iteration
  int double_every = 10;       // iterations per complexity
  int iterations = 90;
  double norm = 2.0;       // p of the Lp multiscale metric
  double gradation = 3.0;  // beta; <= 0: none
  // When set, the previous iteration's field is also interpolated onto
  // the new mesh (point location and P1 interpolation, as a solver
  // restart) and the transfer's L2 error reported.
  bool interpolate = false;
  std::string concurrency{Concurrencies::at<0>::name};
  AdaptOptions adapt;  // thresholds, cycles (the metric interpolated)
  // When set, boundary vertices are placed on this model (CadGeometry).
  const CadModel* model = nullptr;
  // Called after each iteration with its row and the adapted mesh.
  std::function<void(const struct LoopRow&, const Mesh&)> on_iteration;
};

struct LoopRow {
  int iteration = 0;
  double complexity = 0;  // target of this iteration
  std::size_t vertices = 0, tets = 0;
  double seconds = 0;          // metric + adaptation
  double l2_error = 0;         // || u - u_h || on the adapted mesh
  double transfer_error = -1;  // || u - interpolated previous u_h || (when asked)
  double conformity = 0, min_quality = 0;
};

// The target complexity of iteration i (0-based).
double loop_complexity(const LoopOptions& o, int iteration);

// Runs the loop on `mesh` (adapted in place); one row per iteration.
std::vector<LoopRow> adaptive_loop(Mesh& mesh, const LoopOptions& options);

// The CSV of the rows: iteration,complexity,vertices,tets,seconds,l2_error,
// transfer_error,conformity,min_q (header included).
std::string loop_csv(const std::vector<LoopRow>& rows);

}  // namespace metrica
