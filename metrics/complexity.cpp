#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <fmt/core.h>

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

double complexity(const std::vector<Sym6>& field, const std::vector<double>& dual_volume) {
  if (field.size() != dual_volume.size())
    throw InputError(fmt::format("metric field of {} tensors for {} vertex ids", field.size(), dual_volume.size()));
  double c = 0.0;
  for (std::size_t i = 0; i < field.size(); ++i)
    if (dual_volume[i] > 0.0) c += std::sqrt(determinant(field[i])) * dual_volume[i];
  return c;
}

double complexity(const Mesh& mesh, const std::vector<Sym6>& field) { return complexity(field, dual_volumes(mesh)); }

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
