// Bounds on a metric's sizes: h_min <= h <= h_max in every direction and a
// largest anisotropy ratio h_max / h_min of one tensor. Applied to every
// metric an adaptation receives, so that no request is below what double
// precision and the domain can hold, or above the domain's size.
#pragma once

#include <metrica/metrics/sym_tensor.hpp>

#include <limits>
#include <vector>

namespace metrica {

struct MetricBounds {
  double hmin = 0.0;
  double hmax = std::numeric_limits<double>::infinity();
  double max_anisotropy = std::numeric_limits<double>::infinity();
  bool active() const {
    return hmin > 0.0 || hmax < std::numeric_limits<double>::infinity() ||
           max_anisotropy < std::numeric_limits<double>::infinity();
  }
};

// Throws InputError for hmin < 0, hmax <= 0, hmin > hmax, or a ratio < 1.
void check_bounds(const MetricBounds& b);

// Clamps the eigenvalues: l in [1/hmax^2, 1/hmin^2], then raises the
// smallest to l_max / ratio^2. Eigenvectors are kept.
Sym6 clamp_metric(const Sym6& m, const MetricBounds& b);
void clamp_metrics(std::vector<Sym6>& field, const MetricBounds& b);

}  // namespace metrica
