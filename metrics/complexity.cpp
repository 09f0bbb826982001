#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace metrica {

std::vector<double> dual_volumes(const Mesh& mesh) {
  std::vector<double> v(mesh.vertex_capacity(), 0.0);
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& k = mesh.tet(t);
    const double q = 0.25 * tet_volume(mesh.point(k[0]), mesh.point(k[1]), mesh.point(k[2]), mesh.point(k[3]));
    for (VertexId a : k) v[a] += q;
  }
  return v;
}

namespace {
// The sum over vertices of sqrt(det M_i) times the dual volume, M_i =
// metric_of(i).
template <class MetricOf>
double complexity_sum(const std::vector<double>& dual_volume, MetricOf&& metric_of) {
  double c = 0.0;
  for (std::size_t i = 0; i < dual_volume.size(); ++i)
    if (dual_volume[i] > 0.0) c += std::sqrt(spd_determinant(metric_of(i))) * dual_volume[i];
  return c;
}
}  // namespace

double complexity(const std::vector<Sym6>& field, const std::vector<double>& dual_volume) {
  if (field.size() != dual_volume.size())
    throw InputError(fmt::format("metric field of {} tensors for {} vertex ids", field.size(), dual_volume.size()));
  return complexity_sum(dual_volume, [&](std::size_t i) -> const Sym6& { return field[i]; });
}

double complexity(const Mesh& mesh, const std::vector<Sym6>& field) { return complexity(field, dual_volumes(mesh)); }

double complexity(const Mesh& mesh) {
  return complexity_sum(dual_volumes(mesh),
                        [&](std::size_t i) -> const Sym6& { return mesh.metric(static_cast<VertexId>(i)); });
}

int sample_order(double tets, double samples) {
  tets = std::max(1.0, tets);
  // A lattice of order m has (m+1)(m+2)(m+3)/6 points.
  int m = 1;
  while (m < 16 && double(m + 2) * (m + 3) * (m + 4) / 6.0 * tets <= samples) ++m;
  return m;
}

double sampled_tet_complexity(const Point& a, const Point& b, const Point& d, const Point& e,
                              const std::function<Sym6(const Point&)>& metric, int m) {
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; i + j <= m; ++j)
      for (int l = 0; i + j + l <= m; ++l) {
        const int r = m - i - j - l;
        const Point p = (double(i) * a + double(j) * b + double(l) * d + double(r) * e) / double(m);
        sum += std::sqrt(spd_determinant(metric(p)));
        ++count;
      }
  return tet_volume(a, b, d, e) * sum / count;
}

double sampled_complexity(const Mesh& mesh, const std::function<Sym6(const Point&)>& metric, double samples) {
  const int m = sample_order(double(mesh.num_tets()), samples);
  double c = 0.0;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& k = mesh.tet(t);
    c += sampled_tet_complexity(mesh.point(k[0]), mesh.point(k[1]), mesh.point(k[2]), mesh.point(k[3]), metric, m);
  }
  return c;
}

void scale_metrics(std::vector<Sym6>& field, double s) {
  for (auto& m : field)
    for (double& x : m) x *= s;
}

void scale_to_complexity(std::vector<Sym6>& field, const std::vector<double>& dual_volume, double target) {
  if (!(target > 0.0) || !std::isfinite(target))
    throw InputError(fmt::format("the target complexity must be a positive number (got {})", target));
  const double c = complexity(field, dual_volume);
  if (!(c > 0.0)) throw InputError("the metric field has zero complexity; it cannot be scaled to a target");
  // C scales as s^(3/2) when M is multiplied by s.
  scale_metrics(field, std::pow(target / c, 2.0 / 3.0));
}

}  // namespace metrica
