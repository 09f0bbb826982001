#include <metrica/error.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace metrica {

namespace {
constexpr double kH0 = 0.001;

// Cylindrical axes at p: columns e_r, e_t, e_z (e_r = x at the axis).
Matrix3 polar_axes(const Point& p) {
  const double t = std::atan2(p.y(), p.x());
  Matrix3 r;
  r << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;
  return r;
}
}  // namespace

AnalyticMetric analytic_metric_from_name(std::string_view name) {
  if (name == "linear") return AnalyticMetric::linear;
  if (name == "polar-1") return AnalyticMetric::polar1;
  if (name == "polar-2") return AnalyticMetric::polar2;
  throw InputError(fmt::format("unknown analytic metric '{}' (known: linear, polar-1, polar-2)", name));
}

const char* to_string(AnalyticMetric m) {
  switch (m) {
    case AnalyticMetric::linear: return "linear";
    case AnalyticMetric::polar1: return "polar-1";
    case AnalyticMetric::polar2: return "polar-2";
  }
  return "?";
}

std::vector<std::string> analytic_metric_names() { return {"linear", "polar-1", "polar-2"}; }

Sym6 evaluate(AnalyticMetric m, const Point& p) {
  switch (m) {
    case AnalyticMetric::linear: {
      const double hz = kH0 + 2.0 * (0.1 - kH0) * std::abs(p.z() - 0.5);
      // 1 / (h h) as the UGAWG reference files compute it.
      return {1.0 / (0.1 * 0.1), 0.0, 1.0 / (0.1 * 0.1), 0.0, 0.0, 1.0 / (hz * hz)};
    }
    case AnalyticMetric::polar1:
    case AnalyticMetric::polar2: {
      const double r = std::hypot(p.x(), p.y());
      const double hr = kH0 + 2.0 * (0.1 - kH0) * std::abs(r - 0.5);
      double ht = 0.1;
      if (m == AnalyticMetric::polar2) {
        const double d = std::min(10.0 * std::abs(r - 0.5), 1.0);
        ht = 0.1 * d + 0.025 * (1.0 - d);
      }
      return metric_from_sizes(polar_axes(p), Eigen::Vector3d(hr, ht, 0.1));
    }
  }
  return isotropic_metric(1.0);
}

}  // namespace metrica
