#include <metrica/metrics/sym_tensor.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

namespace metrica {

Sym6 metric_from_sizes(const Matrix3& directions, const Eigen::Vector3d& sizes) {
  const Eigen::Vector3d l = sizes.array().square().inverse();
  return to_sym6(directions * l.asDiagonal() * directions.transpose());
}

Eigen3 eigen_decomposition(const Sym6& m) {
  Eigen::SelfAdjointEigenSolver<Matrix3> solver(to_matrix(m));
  return {solver.eigenvalues(), solver.eigenvectors()};
}

bool is_spd(const Sym6& m) {
  for (double x : m)
    if (!std::isfinite(x)) return false;
  return eigen_decomposition(m).values[0] > 0.0;
}

double spd_determinant_by_eigenvalues(const Sym6& m) {
  const Eigen::Vector3d l = eigen_decomposition(m).values.cwiseMax(0.0);
  return l.prod();
}

Sym6 spd_log(const Sym6& m) {
  const auto e = eigen_decomposition(m);
  return to_sym6(e.vectors * e.values.array().log().matrix().asDiagonal() * e.vectors.transpose());
}

Sym6 spd_exp(const Sym6& log_m) {
  const auto e = eigen_decomposition(log_m);
  return to_sym6(e.vectors * e.values.array().exp().matrix().asDiagonal() * e.vectors.transpose());
}

namespace {
// a b for symmetric a, b that commute (polynomials in one matrix), whose
// product is then symmetric: 18 multiplications.
Sym6 commuting_product(const Sym6& a, const Sym6& b) {
  return {a[0] * b[0] + a[1] * b[1] + a[3] * b[3], a[0] * b[1] + a[1] * b[2] + a[3] * b[4],
          a[1] * b[1] + a[2] * b[2] + a[4] * b[4], a[0] * b[3] + a[1] * b[4] + a[3] * b[5],
          a[1] * b[3] + a[2] * b[4] + a[4] * b[5], a[3] * b[3] + a[4] * b[4] + a[5] * b[5]};
}
}  // namespace

// Scaling and squaring (Moler and Van Loan, "Nineteen dubious ways to
// compute the exponential of a matrix", 2003, method 3), carried out on
// three scalars. The trace comes out as a scalar factor; the traceless
// rest D satisfies Cayley-Hamilton, D^3 = p D + q I with p = tr(D^2) / 2
// and q = det D, so every polynomial in X = D / 2^s is a I + b X + c X^2.
// X's norm is brought below 1/2, exp(X) is its Taylor polynomial of degree
// 10 (truncation ~1e-11), and the s squarings act on (a, b, c) alone; one
// matrix product (D^2) assembles the result. No transcendental function
// but one exp: 49 ns a call against 142 ns for the same method on
// matrices (which was 18% of an adaptation's instructions, through the
// tet metrics of the mean ratio). Relative error of v^T M v along any
// eigenvector: 2e-11 at metric anisotropy 1e4, 4e-7 at 1e8 (on matrices:
// 3e-11, 2.5e-8): at 1e8 the quadratic a + b x + c x^2 cancels at the
// smallest eigenvalue. The stored metrics come from spd_exp.
Sym6 spd_exp_fast(const Sym6& log_m) {
  const double t = (log_m[0] + log_m[2] + log_m[5]) / 3.0;
  const Sym6 d{log_m[0] - t, log_m[1], log_m[2] - t, log_m[3], log_m[4], log_m[5] - t};
  const double norm2 = d[0] * d[0] + d[2] * d[2] + d[5] * d[5] + 2.0 * (d[1] * d[1] + d[3] * d[3] + d[4] * d[4]);
  const double det =
      d[0] * (d[2] * d[5] - d[4] * d[4]) - d[1] * (d[1] * d[5] - d[4] * d[3]) + d[3] * (d[1] * d[4] - d[2] * d[3]);
  if (!std::isfinite(norm2 + det + t)) {  // NaN or inf in: NaN out, not an endless halving
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return Sym6{nan, nan, nan, nan, nan, nan};
  }
  int halvings = 0;
  double scale = 1.0;  // 2^-halvings
  while (norm2 * scale * scale > 0.25) {
    scale *= 0.5;
    ++halvings;
  }
  const double p = 0.5 * norm2 * scale * scale, q = det * scale * scale * scale;
  // Taylor: the term X^k / k! = (ta I + tb X + tc X^2), X^(k+1) from
  // X (ta I + tb X + tc X^2) = tc q I + (ta + tc p) X + tb X^2.
  double a = 1.0, b = 0.0, c = 0.0;
  double ta = 1.0, tb = 0.0, tc = 0.0;
  for (int k = 1; k <= 10; ++k) {
    const double inv = 1.0 / k;
    const double na = tc * q * inv, nb = (ta + tc * p) * inv, nc = tb * inv;
    ta = na;
    tb = nb;
    tc = nc;
    a += ta;
    b += tb;
    c += tc;
  }
  // Squarings: (a I + b X + c X^2)^2 with X^3 = p X + q I, X^4 = p X^2 + q X.
  for (int i = 0; i < halvings; ++i) {
    const double na = a * a + 2.0 * b * c * q;
    const double nb = 2.0 * a * b + 2.0 * b * c * p + c * c * q;
    const double nc = b * b + 2.0 * a * c + c * c * p;
    a = na;
    b = nb;
    c = nc;
  }
  // exp(D) = a I + (b s) D + (c s^2) D^2, s = 2^-halvings.
  const Sym6 d2 = commuting_product(d, d);
  const double et = std::exp(t);
  const double ea = et * a, eb = et * b * scale, ec = et * c * scale * scale;
  return {ea + eb * d[0] + ec * d2[0], eb * d[1] + ec * d2[1], ea + eb * d[2] + ec * d2[2],
          eb * d[3] + ec * d2[3],      eb * d[4] + ec * d2[4], ea + eb * d[5] + ec * d2[5]};
}

Matrix3 metric_factor(const Sym6& m) {
  // Cholesky, M = U^T U in closed form (storage xx, xy, yy, xz, yz, zz).
  // Every use of L (lengths, the ideal apex of smoothing, encroachment,
  // the metric Delaunay measure) is invariant under L -> R L with R
  // orthogonal, so the triangular factor serves as well as the symmetric
  // square root, at a fraction of an eigendecomposition (which was 1.3%
  // of an adaptation, through smoothing's ideal apexes).
  const double u00 = std::sqrt(m[0]);
  const double u01 = m[1] / u00, u02 = m[3] / u00;
  const double u11 = std::sqrt(m[2] - u01 * u01);
  const double u12 = (m[4] - u01 * u02) / u11;
  const double u22 = std::sqrt(m[5] - u02 * u02 - u12 * u12);
  Matrix3 u;
  u << u00, u01, u02, 0.0, u11, u12, 0.0, 0.0, u22;
  return u;
}

Sym6 log_euclidean_mean(std::span<const Sym6> metrics, std::span<const double> weights) {
  Sym6 l{};
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const Sym6 li = spd_log(metrics[i]);
    for (int c = 0; c < 6; ++c) l[c] += weights[i] * li[c];
  }
  return spd_exp(l);
}

}  // namespace metrica
