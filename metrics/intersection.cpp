#include <metrica/metrics/intersection.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace metrica {

Sym6 intersect(const Sym6& a, const Sym6& b) {
  // B p = mu A p with P^T A P = I: A = P^-T P^-1, B = P^-T diag(mu) P^-1.
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix3> solver(to_matrix(b), to_matrix(a));
  const Eigen::Vector3d mu = solver.eigenvalues().cwiseMax(1.0);
  const Matrix3 p_inv = solver.eigenvectors().inverse();
  return to_sym6(p_inv.transpose() * mu.asDiagonal() * p_inv);
}

}  // namespace metrica
