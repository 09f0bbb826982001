#include <metrica/error.hpp>
#include <metrica/metrics/metric_bounds.hpp>

#include <fmt/core.h>

#include <algorithm>

namespace metrica {

void check_bounds(const MetricBounds& b) {
  if (!(b.hmin >= 0.0)) throw InputError(fmt::format("hmin must be >= 0 (got {})", b.hmin));
  if (!(b.hmax > 0.0)) throw InputError(fmt::format("hmax must be > 0 (got {})", b.hmax));
  if (b.hmin > b.hmax) throw InputError(fmt::format("hmin {} is larger than hmax {}", b.hmin, b.hmax));
  if (!(b.max_anisotropy >= 1.0))
    throw InputError(fmt::format("the anisotropy ratio must be >= 1 (got {})", b.max_anisotropy));
}

Sym6 clamp_metric(const Sym6& m, const MetricBounds& b) {
  auto e = eigen_decomposition(m);
  const double lo = 1.0 / (b.hmax * b.hmax);
  const double hi = b.hmin > 0.0 ? 1.0 / (b.hmin * b.hmin) : std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) e.values[i] = std::clamp(e.values[i], lo, hi);
  const double floor = e.values.maxCoeff() / (b.max_anisotropy * b.max_anisotropy);
  for (int i = 0; i < 3; ++i) e.values[i] = std::max(e.values[i], floor);
  return to_sym6(e.vectors * e.values.asDiagonal() * e.vectors.transpose());
}

void clamp_metrics(std::vector<Sym6>& field, const MetricBounds& b) {
  if (!b.active()) return;
  for (auto& m : field) m = clamp_metric(m, b);
}

}  // namespace metrica
