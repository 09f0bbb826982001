#include <metrica/predicates/edge_weight.hpp>
#include <metrica/tet_topology.hpp>

namespace metrica {

std::array<double, 6> edge_weights(const TetPoints& k, const Sym6& m) {
  std::array<double, 6> w;
  const double vol = metric_volume(k, m);
  if (!(vol > 0.0)) {
    w.fill(-std::numeric_limits<double>::infinity());
    return w;
  }
  const Matrix3 mm = to_matrix(m);
  auto dot = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return x.dot(mm * y); };
  for (int i = 0; i < 6; ++i) {
    const int a = kEdgeVertex[i][0], b = kEdgeVertex[i][1];
    const int opposite = 5 - i;  // kEdgeVertex pairs i with 5 - i
    const int c = kEdgeVertex[opposite][0], d = kEdgeVertex[opposite][1];
    const Eigen::Vector3d e = k[d] - k[c], u = k[a] - k[c], v = k[b] - k[c];
    w[i] = (dot(e, e) * dot(u, v) - dot(e, u) * dot(e, v)) / (6.0 * vol);
  }
  return w;
}

}  // namespace metrica
