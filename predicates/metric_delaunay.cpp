#include <metrica/predicates/metric_delaunay.hpp>

#include <Eigen/LU>

namespace metrica {

double delaunay_measure(const TetPoints& k, const Point& p, const Matrix3& l) {
  // Circumcentre O of the mapped tet, relative to its first vertex a:
  // 2 (x_i - a) . O = |x_i - a|^2 for the three other vertices.
  const Point a = l * k[0];
  Matrix3 rows;
  Eigen::Vector3d rhs;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = l * k[i + 1] - a;
    rows.row(i) = 2.0 * e.transpose();
    rhs[i] = e.squaredNorm();
  }
  const double det = rows.determinant();
  if (det == 0.0 || !std::isfinite(det)) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d o = rows.inverse() * rhs;
  const double radius = o.norm();
  if (!(radius > 0.0)) return std::numeric_limits<double>::infinity();
  return (l * p - a - o).norm() / radius;
}

}  // namespace metrica
