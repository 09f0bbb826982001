// The mean-ratio comparison used by flips and smoothing: a new
// configuration replaces an old one only when its worst element is better
// by a relative margin, so that round-off never makes two configurations
// flip back and forth.
#pragma once

#include <metrica/metrics/space.hpp>

#include <algorithm>
#include <limits>
#include <span>

namespace metrica {

inline constexpr double kQualityMargin = 1e-6;

inline bool improves_min_quality(double before, double after, double margin = kQualityMargin) {
  return after > before + margin * std::max(std::abs(before), 1e-300);
}

// The value `after` must exceed for improves_min_quality(before, after).
inline double improvement_bar(double before, double margin = kQualityMargin) {
  return before + margin * std::max(std::abs(before), 1e-300);
}

template <MetricSpace S>
double min_mean_ratio(const Mesh& mesh, std::span<const TetVertices> tets) {
  double q = std::numeric_limits<double>::infinity();
  for (const auto& t : tets) q = std::min(q, S::mean_ratio(mesh, t));
  return q;
}

}  // namespace metrica
