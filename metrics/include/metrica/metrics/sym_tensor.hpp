// Symmetric 3x3 tensors (metrics) on fixed-size Eigen types.
//
// Storage is the libMeshb order (xx, xy, yy, xz, yz, zz) in a Sym6, so a
// tensor read from a .solb is used as is. The SPD logarithm and exponential
// go through the symmetric eigendecomposition: M = R diag(l) R^T gives
// log M = R diag(log l) R^T. Eigen's iterative solver (tridiagonalisation
// + implicit QR) keeps eigenvalues to about machine precision relative to
// the largest, which is what anisotropy ratios of 1e8 need; the closed-form
// 3x3 solver loses the small eigenvalues there.
#pragma once

#include <metrica/ids.hpp>

#include <Eigen/Core>

#include <cmath>
#include <span>

namespace metrica {

using Matrix3 = Eigen::Matrix3d;

inline Matrix3 to_matrix(const Sym6& s) {
  Matrix3 m;
  m << s[0], s[1], s[3], s[1], s[2], s[4], s[3], s[4], s[5];
  return m;
}

// Takes the symmetric part (averaging the off-diagonal pairs).
inline Sym6 to_sym6(const Matrix3& m) {
  return {m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), m(1, 1), 0.5 * (m(0, 2) + m(2, 0)), 0.5 * (m(1, 2) + m(2, 1)), m(2, 2)};
}

// The isotropic metric of size h: M = h^-2 I.
inline Sym6 isotropic_metric(double h) {
  const double a = 1.0 / (h * h);
  return {a, 0, a, 0, 0, a};
}

// A metric from its principal sizes and directions: M = R diag(h^-2) R^T,
// R's columns the directions (orthonormal).
Sym6 metric_from_sizes(const Matrix3& directions, const Eigen::Vector3d& sizes);

struct Eigen3 {
  Eigen::Vector3d values;  // ascending
  Matrix3 vectors;         // columns
};
Eigen3 eigen_decomposition(const Sym6& m);

// True when every entry is finite and every eigenvalue positive.
bool is_spd(const Sym6& m);

// SPD log and exp (the log-Euclidean framework of Arsigny et al., 2006).
Sym6 spd_log(const Sym6& m);
Sym6 spd_exp(const Sym6& log_m);
// The exponential by scaling and squaring of a Taylor polynomial: several
// times faster than spd_exp, with a relative error of v^T M v up to ~2e-8
// at anisotropy 1e8 (3e-11 at 1e4; 1e-15 for spd_exp). For measuring
// (the metric of a tet in quality evaluations), not for metrics that are
// stored.
Sym6 spd_exp_fast(const Sym6& log_m);

// L with M = L^T L, upper triangular (the Cholesky factor): maps a vector
// into the metric's Euclidean space, |L v| = sqrt(v^T M v).
Matrix3 metric_factor(const Sym6& m);

inline double metric_norm2(const Sym6& m, const Eigen::Vector3d& v) {
  return m[0] * v.x() * v.x() + m[2] * v.y() * v.y() + m[5] * v.z() * v.z() +
         2.0 * (m[1] * v.x() * v.y() + m[3] * v.x() * v.z() + m[4] * v.y() * v.z());
}

// The log-Euclidean mean exp(sum w_i log M_i) (sum w_i = 1).
Sym6 log_euclidean_mean(std::span<const Sym6> metrics, std::span<const double> weights);

inline double determinant(const Sym6& m) { return to_matrix(m).determinant(); }

// det M from the eigenvalues (clamped at 0): spd_determinant's slow path.
double spd_determinant_by_eigenvalues(const Sym6& m);

// det M of a tensor meant to be SPD, from its entries unless they cancel
// (a rotated, nearly rank-deficient M, as a planar front's multiscale
// metric is: the entries' determinant falls far below the product of the
// diagonal, Hadamard's bound, and may come out negative), then from its
// eigenvalues, clamped at 0. Every measure in a metric (volume, mean ratio,
// size) takes its determinant here.
inline double spd_determinant(const Sym6& m) {
  const double det = determinant(m);
  if (det > 1e-6 * (m[0] * m[2] * m[5])) return det;
  return spd_determinant_by_eigenvalues(m);
}

// The adjugate of m (det(m) m^-1, symmetric), in the same storage.
inline Sym6 adjugate(const Sym6& m) {
  return {m[2] * m[5] - m[4] * m[4], m[3] * m[4] - m[1] * m[5], m[0] * m[5] - m[3] * m[3],
          m[1] * m[4] - m[2] * m[3], m[1] * m[3] - m[0] * m[4], m[0] * m[2] - m[1] * m[1]};
}

// m v for symmetric m.
inline Eigen::Vector3d sym_times(const Sym6& m, const Eigen::Vector3d& v) {
  return {m[0] * v.x() + m[1] * v.y() + m[3] * v.z(), m[1] * v.x() + m[2] * v.y() + m[4] * v.z(),
          m[3] * v.x() + m[4] * v.y() + m[5] * v.z()};
}

}  // namespace metrica
