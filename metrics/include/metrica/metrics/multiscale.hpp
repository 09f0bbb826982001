// The multiscale metric (Loseille & Alauzet, "Continuous mesh framework",
// SIAM J. Numer. Anal. 49, 2011, parts I-II): the metric that minimises the
// L^p norm of the P1 interpolation error of a field u for a given
// complexity N,
//   M_i = D_N det|H_i|^(-1/(2p+3)) |H_i|,   D_N chosen so that C(M) = N,
// with H the recovered Hessian (recovery.hpp) and |H| its absolute value
// (absolute eigenvalues). Then, as in refine's multiscale command, bounds
// (h_min, h_max, anisotropy) and gradation are applied and the field is
// scaled again, a few times, until its complexity is back at N.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/metrics/gradation.hpp>
#include <metrica/metrics/metric_bounds.hpp>

#include <vector>

namespace metrica {

struct MultiscaleOptions {
  double complexity = 1000.0;
  double norm = 2.0;    // p, in [1, inf)
  MetricBounds bounds;  // h_max defaults to the domain's largest extent
  bool gradation = true;
  GradationOptions gradation_options;
  // The recovered Hessian at boundary vertices replaced by their interior
  // neighbours' (recovery.hpp: extrapolate_hessian_to_boundary).
  bool extrapolate_boundary = true;
  int max_relaxations = 8;             // scale / bound / grade rounds
  double complexity_tolerance = 5e-3;  // stop when |C/N - 1| is below
};

struct MultiscaleReport {
  double complexity = 0;  // of the result
  int relaxations = 0;
  double hessian_seconds = 0, gradation_seconds = 0, total_seconds = 0;
};

// `values` indexed by vertex id. InputError for a complexity <= 0, p < 1,
// non-finite values, or a field whose Hessian vanishes everywhere.
std::vector<Sym6> multiscale_metric(const Mesh& mesh, const std::vector<double>& values,
                                    const MultiscaleOptions& options, MultiscaleReport* report = nullptr);

// Several fields of one solution (velocity components and pressure): each
// field's metric is scaled to the complexity N on its own, so that every
// field asks for sizes at the same cost whatever its magnitude; the metrics
// are intersected vertex by vertex (intersection.hpp), then bounded, graded
// and scaled back to N. A field whose Hessian vanishes (a component that is
// linear or constant) asks for nothing and is left out with a warning;
// InputError when every field does.
std::vector<Sym6> multiscale_metric(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                                    const MultiscaleOptions& options, MultiscaleReport* report = nullptr);

// The same from a Hessian field (for users who recover it themselves).
std::vector<Sym6> multiscale_metric_from_hessian(const Mesh& mesh, std::vector<Sym6> hessian,
                                                 const MultiscaleOptions& options, MultiscaleReport* report = nullptr);

}  // namespace metrica
