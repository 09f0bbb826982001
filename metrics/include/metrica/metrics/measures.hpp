// Lengths, volumes and shape of simplices measured in a metric: the
// UGAWG measures of the seed's appendix A, as pure functions of points and
// tensors. The Space policies (space.hpp) choose which tensor to use.
#pragma once

#include <metrica/geometry.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/metrics/unit_band.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace metrica {

using TetPoints = std::array<Point, 4>;

// Eq. (length) of the seed, appendix A: the length of edge v between
// endpoints with metrics Ma and Mb, exact when the size varies
// geometrically along the edge; the mean when the two lengths nearly agree.
// That is the logarithmic mean of la and lb. With x = (la - lb) / (la + lb),
// ln(la / lb) = 2 atanh x, so L = (la + lb) / 2 * x / atanh x, and
// atanh x / x = 1 + x^2/3 + x^4/5 + ...: for |x| < 1/8 (the lengths within
// a ratio of 1.29, most edges of a unit mesh) eight terms give it to
// rounding (the next is below 2^-48 / 17) without a logarithm (the log was
// 4% of an adaptation's instructions).
inline double ugawg_length(double la, double lb) {
  const double sum = la + lb;
  if (!(sum > 0.0)) return 0.5 * sum;  // both 0 (or NaN)
  const double x = (la - lb) / sum, x2 = x * x;
  if (x2 < 1.0 / 64.0) {
    const double atanh_over_x =
        1.0 +
        x2 * (1.0 / 3 +
              x2 * (1.0 / 5 + x2 * (1.0 / 7 + x2 * (1.0 / 9 + x2 * (1.0 / 11 + x2 * (1.0 / 13 + x2 * (1.0 / 15)))))));
    return 0.5 * sum / atanh_over_x;
  }
  if (la < lb) std::swap(la, lb);  // the same rounding either way round
  return (la - lb) / std::log(la / lb);
}
inline double ugawg_length(const Eigen::Vector3d& v, const Sym6& ma, const Sym6& mb) {
  return ugawg_length(std::sqrt(metric_norm2(ma, v)), std::sqrt(metric_norm2(mb, v)));
}

// Is that length in `band`? It is the logarithmic mean of the lengths at
// the two ends, which lies between them: when both ends are inside the
// band (or both on one side of it) the squared lengths decide, without a
// root or a logarithm.
inline bool ugawg_length_in(const UnitBand& band, const Eigen::Vector3d& v, const Sym6& ma, const Sym6& mb) {
  const double a2 = metric_norm2(ma, v), b2 = metric_norm2(mb, v);
  const double lo2 = band.lo * band.lo, hi2 = band.hi * band.hi;
  const double min2 = std::min(a2, b2), max2 = std::max(a2, b2);
  if (min2 >= lo2 && max2 <= hi2) return true;
  if (max2 < lo2 || min2 > hi2) return false;
  return band.contains(ugawg_length(std::sqrt(a2), std::sqrt(b2)));
}

// |K| sqrt(det M): the volume of K in the constant metric M.
inline double metric_volume(const TetPoints& p, const Sym6& m) {
  return tet_volume(p[0], p[1], p[2], p[3]) * std::sqrt(spd_determinant(m));
}

// Eq. (quality), appendix A: the mean ratio
//   Q = 36 / 3^(1/3) (|K| sqrt(det M))^(2/3) / sum_e v_e^T M v_e,
// 1 for the regular tet in M, 0 when flat; negative volume gives a negative
// value (sign kept so that inversion is never mistaken for quality).
inline double mean_ratio(const TetPoints& p, const Sym6& m) {
  const double vol = metric_volume(p, m);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) sum += metric_norm2(m, p[j] - p[i]);
  if (!(sum > 0.0)) return 0.0;
  static const double kNorm = 36.0 / std::cbrt(3.0);
  const double q = kNorm * std::cbrt(vol * vol) / sum;
  return vol < 0.0 ? -q : q;
}

// The mean ratio cubed is 36^3 / 3 (|K| sqrt(det M))^2 / sum^3, that is
// kMeanRatioCubedNorm volume6^2 det M / sum^3 with |K| = volume6 / 6.
inline constexpr double kMeanRatioCubedNorm = 36.0 * 36.0 / 3.0;

// The cube of mean_ratio (sign kept), without its cube root, from its
// parts: six times the tet's signed volume, det M and the sum of the six
// edges' v^T M v. For finding the smallest of many mean ratios, which is
// the cube root of the smallest cube (the root was 7% of an adaptation in
// smoothing), where a moving vertex leaves most parts fixed.
inline double mean_ratio_cubed(double volume6, double det, double edge_norms) {
  if (!(edge_norms > 0.0)) return 0.0;
  const double q3 = kMeanRatioCubedNorm * volume6 * volume6 * det / (edge_norms * edge_norms * edge_norms);
  return volume6 < 0.0 ? -q3 : q3;
}

// The same from the points and the constant metric.
inline double mean_ratio_cubed(const TetPoints& p, const Sym6& m) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) sum += metric_norm2(m, p[j] - p[i]);
  return mean_ratio_cubed(orient3d_fast(p[0], p[1], p[2], p[3]), spd_determinant(m), sum);
}

inline Point centroid(const TetPoints& p) { return 0.25 * (p[0] + p[1] + p[2] + p[3]); }

}  // namespace metrica
