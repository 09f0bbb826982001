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

// What a vertex's metric needs for growing it and for testing containment,
// kept up to date as the metric changes.
struct Cached {
  Eigen3 eig;
  Matrix3 inverse;
  void set(const Sym6& m) {
    eig = eigen_decomposition(m);
    inverse = eig.vectors * eig.values.cwiseInverse().asDiagonal() * eig.vectors.transpose();
  }
};

// The eigenvalues of M_p grown along e (same eigenvectors).
Eigen::Vector3d grown_values(const Sym6& m, const Cached& c, const Eigen::Vector3d& e, double log_beta,
                             const GradationOptions& o) {
  const double metric_part = 1.0 + std::sqrt(metric_norm2(m, e)) * log_beta;
  if (o.space == GradationSpace::metric) return c.eig.values / (metric_part * metric_part);
  Eigen::Vector3d l = c.eig.values;
  const double len = e.norm();
  for (int i = 0; i < 3; ++i) {
    const double phys_part = 1.0 + std::sqrt(l[i]) * len * log_beta;
    const double eta = std::pow(phys_part, o.t) * std::pow(metric_part, 1.0 - o.t);
    l[i] /= eta * eta;
  }
  return l;
}

// Limits M_q by M_p grown along e; true when M_q changed by more than tol.
bool limit(Sym6& mq, Cached& cq, const Sym6& mp, const Cached& cp, const Eigen::Vector3d& e, double log_beta,
           const GradationOptions& o) {
  const Eigen::Vector3d l = grown_values(mp, cp, e, log_beta, o);
  // G <= M_q when the largest eigenvalue of G M_q^-1 is <= 1; its trace
  // bounds it (G M_q^-1 is similar to a PSD matrix), and is cheap.
  double trace = 0.0;
  for (int i = 0; i < 3; ++i) trace += l[i] * cp.eig.vectors.col(i).dot(cq.inverse * cp.eig.vectors.col(i));
  if (trace <= 1.0) return false;
  const Sym6 g = to_sym6(cp.eig.vectors * l.asDiagonal() * cp.eig.vectors.transpose());
  const Sym6 x = intersect(mq, g);
  double scale = 0.0, diff = 0.0;
  for (int c = 0; c < 6; ++c) {
    scale = std::max(scale, std::abs(mq[c]));
    diff = std::max(diff, std::abs(x[c] - mq[c]));
  }
  if (diff == 0.0) return false;
  mq = x;
  cq.set(mq);
  return diff > o.tolerance * scale;
}

}  // namespace

GradationStats limit_gradation(const Mesh& mesh, std::vector<Sym6>& field, const GradationOptions& o) {
  if (!(o.beta >= 1.0)) throw InputError(fmt::format("the gradation must be >= 1 (got {})", o.beta));
  if (field.size() != mesh.vertex_capacity())
    throw InputError(fmt::format("metric field of {} tensors for {} vertex ids", field.size(), mesh.vertex_capacity()));
  const double log_beta = std::log(o.beta);
  const auto edges = unique_edges(mesh);
  std::vector<Cached> cache(field.size());
  for (VertexId v = 0; v < field.size(); ++v)
    if (mesh.vertex_alive(v)) cache[v].set(field[v]);
  GradationStats stats;
  for (stats.passes = 1; stats.passes <= o.max_passes; ++stats.passes) {
    stats.changed_last_pass = 0;
    for (const auto& [p, q] : edges) {
      const Eigen::Vector3d e = mesh.point(q) - mesh.point(p);
      stats.changed_last_pass += limit(field[q], cache[q], field[p], cache[p], e, log_beta, o);
      stats.changed_last_pass += limit(field[p], cache[p], field[q], cache[q], e, log_beta, o);
    }
    if (stats.changed_last_pass == 0) break;
  }
  stats.passes = std::min(stats.passes, o.max_passes);
  return stats;
}

}  // namespace metrica
