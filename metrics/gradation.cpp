#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/gradation.hpp>
#include <metrica/metrics/intersection.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica {

GradationSpace gradation_space_from_name(std::string_view name) {
  if (name == "metric") return GradationSpace::metric;
  if (name == "mixed") return GradationSpace::mixed;
  throw InputError(fmt::format("unknown gradation space '{}' (known: mixed, metric)", name));
}

namespace {

Sym6 grow(const Sym6& m, const Eigen::Vector3d& e, double log_beta, const GradationOptions& o) {
  const double lm = std::sqrt(metric_norm2(m, e));
  const double metric_part = 1.0 + lm * log_beta;
  if (o.space == GradationSpace::metric) {
    const double s = 1.0 / (metric_part * metric_part);
    Sym6 g = m;
    for (double& x : g) x *= s;
    return g;
  }
  auto d = eigen_decomposition(m);
  const double len = e.norm();
  for (int i = 0; i < 3; ++i) {
    const double phys_part = 1.0 + std::sqrt(d.values[i]) * len * log_beta;
    const double eta = std::pow(phys_part, o.t) * std::pow(metric_part, 1.0 - o.t);
    d.values[i] /= eta * eta;
  }
  return to_sym6(d.vectors * d.values.asDiagonal() * d.vectors.transpose());
}

bool differs(const Sym6& a, const Sym6& b, double tol) {
  double scale = 0.0, diff = 0.0;
  for (int c = 0; c < 6; ++c) {
    scale = std::max(scale, std::abs(a[c]));
    diff = std::max(diff, std::abs(a[c] - b[c]));
  }
  return diff > tol * scale;
}

}  // namespace

GradationStats limit_gradation(const Mesh& mesh, std::vector<Sym6>& field, const GradationOptions& o) {
  if (!(o.beta >= 1.0)) throw InputError(fmt::format("the gradation must be >= 1 (got {})", o.beta));
  if (field.size() != mesh.vertex_capacity())
    throw InputError(fmt::format("metric field of {} tensors for {} vertex ids", field.size(), mesh.vertex_capacity()));
  const double log_beta = std::log(o.beta);
  const auto edges = unique_edges(mesh);
  GradationStats stats;
  for (stats.passes = 1; stats.passes <= o.max_passes; ++stats.passes) {
    stats.changed_last_pass = 0;
    for (const auto& [p, q] : edges) {
      const Eigen::Vector3d e = mesh.point(q) - mesh.point(p);
      const Sym6 mq = intersect(field[q], grow(field[p], e, log_beta, o));
      const Sym6 mp = intersect(field[p], grow(field[q], e, log_beta, o));
      if (differs(mq, field[q], o.tolerance)) ++stats.changed_last_pass;
      if (differs(mp, field[p], o.tolerance)) ++stats.changed_last_pass;
      field[q] = mq;
      field[p] = mp;
    }
    if (stats.changed_last_pass == 0) break;
  }
  stats.passes = std::min(stats.passes, o.max_passes);
  return stats;
}

}  // namespace metrica
