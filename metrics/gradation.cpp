#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/gradation.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <Eigen/Eigenvalues>
#include <fmt/core.h>

#include <cmath>

namespace metrica {

GradationSpace gradation_space_from_name(std::string_view name) {
  if (name == "metric") return GradationSpace::metric;
  if (name == "mixed") return GradationSpace::mixed;
  throw InputError(fmt::format("unknown gradation space '{}' (known: mixed, metric)", name));
}

namespace {

// What a vertex's metric needs for growing it and for intersecting with
// it, kept up to date as the metric changes: M = V diag(l) V^T, and
// L^-1 = V diag(l^-1/2) with M = L^T L.
struct Cached {
  Eigen3 eig;
  Matrix3 l_inv;
  void set(const Sym6& m) {
    eig = eigen_decomposition(m);
    l_inv = eig.vectors * eig.values.cwiseSqrt().cwiseInverse().asDiagonal();
  }
};

// The eigenvalues of M_p grown along e (same eigenvectors).
Eigen::Vector3d grown_values(const Sym6& m, const Cached& c, const Eigen::Vector3d& e, double log_beta,
                             const GradationOptions& o) {
  const double metric_part = 1.0 + std::sqrt(metric_norm2(m, e)) * log_beta;
  if (o.space == GradationSpace::metric) return c.eig.values / (metric_part * metric_part);
  // l_i / eta_i^2 = l_i phys_i^(-2t) metric^(-2(1-t)); t = 1/8 (the
  // default) makes the physical factor a double square root, no pow.
  Eigen::Vector3d l = c.eig.values * std::pow(metric_part, -2.0 * (1.0 - o.t));
  const double len = e.norm();
  const bool eighth = o.t == 0.125;
  for (int i = 0; i < 3; ++i) {
    const double phys_part = 1.0 + std::sqrt(c.eig.values[i]) * len * log_beta;
    l[i] *= eighth ? 1.0 / std::sqrt(std::sqrt(phys_part)) : std::pow(phys_part, -2.0 * o.t);
  }
  return l;
}

// Limits M_q by G, M_p grown along e: M_q <- M_q ∩ G, by simultaneous
// reduction in M_q's own space, X = L_q^-T G L_q^-1 (intersection.hpp).
// True when M_q changed by more than tol.
bool limit(Sym6& mq, Cached& cq, const Sym6& mp, const Cached& cp, const Eigen::Vector3d& e, double log_beta,
           const GradationOptions& o) {
  const Eigen::Vector3d l = grown_values(mp, cp, e, log_beta, o);
  const Matrix3 w = cq.l_inv.transpose() * cp.eig.vectors;
  const Matrix3 x = w * l.asDiagonal() * w.transpose();
  // G <= M_q exactly when X <= I. Most edges pass this test: the
  // closed-form eigenvalues decide it, cheaply.
  Eigen::SelfAdjointEigenSolver<Matrix3> direct;
  direct.computeDirect(x, Eigen::EigenvaluesOnly);
  if (direct.eigenvalues().maxCoeff() <= 1.0 + 1e-12) return false;
  Eigen::SelfAdjointEigenSolver<Matrix3> solver(x);
  const Eigen::Vector3d mu = solver.eigenvalues().cwiseMax(1.0);
  const Matrix3 r = cq.eig.vectors * cq.eig.values.cwiseSqrt().asDiagonal() * solver.eigenvectors();
  const Sym6 next = to_sym6(r * mu.asDiagonal() * r.transpose());
  double scale = 0.0, diff = 0.0;
  for (int c = 0; c < 6; ++c) {
    scale = std::max(scale, std::abs(mq[c]));
    diff = std::max(diff, std::abs(next[c] - mq[c]));
  }
  mq = next;
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
    // Alternate sweep directions (symmetric Gauss-Seidel), so that a small
    // size travels across the mesh in a few passes whichever way it goes.
    const bool forward = stats.passes % 2 == 1;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const auto& [p, q] = edges[forward ? k : edges.size() - 1 - k];
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
