#include <metrica/metrics/sym_tensor.hpp>

#include <cmath>

#include <Eigen/Eigenvalues>

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

Sym6 spd_log(const Sym6& m) {
  const auto e = eigen_decomposition(m);
  return to_sym6(e.vectors * e.values.array().log().matrix().asDiagonal() * e.vectors.transpose());
}

Sym6 spd_exp(const Sym6& log_m) {
  const auto e = eigen_decomposition(log_m);
  return to_sym6(e.vectors * e.values.array().exp().matrix().asDiagonal() * e.vectors.transpose());
}

Sym6 spd_exp_fast(const Sym6& log_m) {
  Eigen::SelfAdjointEigenSolver<Matrix3> solver;
  solver.computeDirect(to_matrix(log_m));
  const Eigen::Vector3d v = solver.eigenvalues().array().exp();
  return to_sym6(solver.eigenvectors() * v.asDiagonal() * solver.eigenvectors().transpose());
}

Matrix3 metric_factor(const Sym6& m) {
  const auto e = eigen_decomposition(m);
  return e.values.array().sqrt().matrix().asDiagonal() * e.vectors.transpose();
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
