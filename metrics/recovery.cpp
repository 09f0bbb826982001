#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/metrics/recovery.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/numbering.hpp>

#include <Eigen/LU>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace metrica {

namespace {

// Volume-weighted projection of the P1 gradients of `ncomp` fields stored
// with stride `ncomp` (component c of vertex v at values[v * ncomp + c]).
// Returns for each vertex the ncomp gradients, row c = gradient of field c.
std::vector<Eigen::Matrix3d> project_gradients(const Mesh& mesh, const double* values, int ncomp) {
  std::vector<Eigen::Matrix3d> sum(mesh.vertex_capacity(), Eigen::Matrix3d::Zero());
  std::vector<double> weight(mesh.vertex_capacity(), 0.0);
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& k = mesh.tet(t);
    Eigen::Matrix3d j;  // rows: edge vectors from vertex 0
    for (int i = 0; i < 3; ++i) j.row(i) = (mesh.point(k[i + 1]) - mesh.point(k[0])).transpose();
    const double vol = j.determinant() / 6.0;
    const Eigen::Matrix3d j_inv = j.inverse();
    Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
    for (int c = 0; c < ncomp; ++c) {
      const double u0 = values[static_cast<std::size_t>(k[0]) * ncomp + c];
      Eigen::Vector3d du;
      for (int i = 0; i < 3; ++i) du[i] = values[static_cast<std::size_t>(k[i + 1]) * ncomp + c] - u0;
      g.row(c) = (j_inv * du).transpose();  // j g = du
    }
    for (VertexId v : k) {
      sum[v] += vol * g;
      weight[v] += vol;
    }
  }
  for (std::size_t v = 0; v < sum.size(); ++v)
    if (weight[v] > 0.0) sum[v] /= weight[v];
  return sum;
}

void check_values(const Mesh& mesh, const std::vector<double>& values) {
  if (values.size() != mesh.vertex_capacity())
    throw InputError(
        fmt::format("field of {} values for a mesh of {} vertex ids", values.size(), mesh.vertex_capacity()));
  for (std::size_t v = 0; v < values.size(); ++v)
    if (mesh.vertex_alive(static_cast<VertexId>(v)) && !std::isfinite(values[v]))
      throw InputError(fmt::format("field value at vertex {} is not finite ({})", numbered(v), values[v]));
}

}  // namespace

std::vector<Eigen::Vector3d> recover_gradient(const Mesh& mesh, const std::vector<double>& values) {
  check_values(mesh, values);
  const auto g = project_gradients(mesh, values.data(), 1);
  std::vector<Eigen::Vector3d> out(g.size());
  for (std::size_t v = 0; v < g.size(); ++v) out[v] = g[v].row(0).transpose();
  return out;
}

std::vector<Sym6> recover_hessian(const Mesh& mesh, const std::vector<double>& values) {
  return recover_hessian(mesh, recover_gradient(mesh, values));
}

std::vector<Sym6> recover_hessian(const Mesh& mesh, const std::vector<Eigen::Vector3d>& grad) {
  std::vector<double> flat(3 * grad.size());
  for (std::size_t v = 0; v < grad.size(); ++v)
    for (int c = 0; c < 3; ++c) flat[3 * v + c] = grad[v][c];
  const auto h = project_gradients(mesh, flat.data(), 3);
  std::vector<Sym6> out(h.size());
  for (std::size_t v = 0; v < h.size(); ++v) out[v] = to_sym6(h[v]);
  return out;
}

int extrapolate_hessian_to_boundary(const Mesh& mesh, std::vector<Sym6>& hessian) {
  const std::size_t n = mesh.vertex_capacity();
  if (hessian.size() != n)
    throw InputError(fmt::format("Hessian field of {} tensors for {} vertex ids", hessian.size(), n));
  // 0: has its own value (interior), 1: waits for a donor, 2: filled this pass.
  std::vector<std::uint8_t> state(n, 0);
  std::size_t waiting = 0;
  for (VertexId v = 0; v < n; ++v)
    if (mesh.vertex_alive(v) && mesh.vertex_class(v) != VertexClass::interior) {
      state[v] = 1;
      ++waiting;
    }
  if (waiting == 0) return 0;
  // Donors are counted once per edge: a pair (v, w) is met in every tet of
  // the edge's shell, so each donor's weight is the number of tets sharing
  // the edge; dividing by the summed weight makes it a weighted mean, which
  // favours neighbours joined by many tets (the well-connected ones).
  std::vector<Sym6> sum(n);
  std::vector<double> weight(n);
  int passes = 0;
  while (waiting > 0) {
    ++passes;
    std::fill(sum.begin(), sum.end(), Sym6{});
    std::fill(weight.begin(), weight.end(), 0.0);
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      if (!mesh.tet_alive(t)) continue;
      const auto& k = mesh.tet(t);
      for (int i = 0; i < 4; ++i) {
        if (state[k[i]] != 1) continue;
        for (int j = 0; j < 4; ++j) {
          if (j == i || state[k[j]] == 1) continue;
          for (int c = 0; c < 6; ++c) sum[k[i]][c] += hessian[k[j]][c];
          weight[k[i]] += 1.0;
        }
      }
    }
    std::size_t filled = 0;
    for (VertexId v = 0; v < n; ++v) {
      if (state[v] != 1 || weight[v] == 0.0) continue;
      for (int c = 0; c < 6; ++c) hessian[v][c] = sum[v][c] / weight[v];
      state[v] = 2;
      ++filled;
    }
    if (filled == 0) break;  // a boundary component with no interior vertex anywhere: keep its values
    waiting -= filled;
    for (auto& s : state)
      if (s == 2) s = 0;
  }
  return passes;
}

}  // namespace metrica
