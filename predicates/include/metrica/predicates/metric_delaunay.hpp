// The anisotropic Delaunay criterion of the seed (section 3.1, eqs. (3)-(4),
// after Dobrzynski & Frey 2008 and Borouchaki et al. 1997).
//
// The Delaunay measure of a point p with respect to K = (x1..x4) in a
// constant metric M is alpha_M(p, K) = d_M(O_K, p) / d_M(O_K, x1), O_K the
// circumcentre of K in M: alpha < 1 when p is inside K's circumsphere in M.
// Distances in M are Euclidean distances after the map x -> L x (M = L^T L),
// so the measure is the classical one on mapped points. The criterion says
// that p violates K's empty-sphere property when
//     alpha_{M_p}(p, K) < 1   and   sum_i alpha_{M_xi}(p, K) + alpha_{M_p}(p, K) < 5:
// the test in the metric of p, and the mean over the 5 metrics of K's
// vertices and p. The first condition is a sign, taken by the Precision
// policy on the mapped points (one rounded construction); the mean is a
// measure, evaluated in double. In a constant metric the two conditions
// coincide, and the criterion is the exact insphere of that metric.
#pragma once

#include <metrica/metrics/measures.hpp>
#include <metrica/predicates/precision.hpp>

#include <array>
#include <limits>

namespace metrica {

inline Point map_point(const Matrix3& l, const Point& p) { return l * p; }

// +1 when e is strictly inside the circumsphere of k (any orientation of k)
// after mapping by L, 0 on it or when the mapped k is flat, -1 outside.
template <Precision P>
int metric_insphere(const TetPoints& k, const Point& e, const Matrix3& l) {
  const Point a = map_point(l, k[0]), b = map_point(l, k[1]), c = map_point(l, k[2]), d = map_point(l, k[3]);
  const int o = P::orient3d(a, b, c, d);
  return o * P::insphere(a, b, c, d, map_point(l, e));
}

// alpha_M(p, K) of eq. (3), with M given by its factor L; +inf when the
// mapped K is flat (no circumsphere: never "inside").
double delaunay_measure(const TetPoints& k, const Point& p, const Matrix3& l);

// Eq. (4): true when p violates the empty circumsphere of K, measured with
// the metrics mk of K's vertices and mp of p.
template <Precision P>
bool metric_delaunay_violated(const TetPoints& k, const Point& p, const std::array<Sym6, 4>& mk, const Sym6& mp) {
  const Matrix3 lp = metric_factor(mp);
  if (metric_insphere<P>(k, p, lp) <= 0) return false;
  int same = 0;
  for (const auto& m : mk) same += (m == mp);
  if (same == 4) return true;  // constant metric: the sign above decides
  const double alpha_p = delaunay_measure(k, p, lp);
  double sum = alpha_p;
  for (const auto& m : mk) sum += (m == mp) ? alpha_p : delaunay_measure(k, p, metric_factor(m));
  return sum < 5.0;
}

}  // namespace metrica
