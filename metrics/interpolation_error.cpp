#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/metrics/interpolation_error.hpp>
#include <metrica/metrics/quadrature.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica {
namespace {

void check_values(const Mesh& mesh, const std::vector<double>& values, const char* what) {
  if (values.size() != mesh.vertex_capacity())
    throw InputError(
        fmt::format("{}: {} values for a mesh of {} vertex ids", what, values.size(), mesh.vertex_capacity()));
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v) && !std::isfinite(values[v]))
      throw InputError(fmt::format("{}: the value at vertex {} is not finite", what, numbered(v)));
}

// sqrt( sum_T |T| sum_q w_q e(T, q)^2 ) over the live tets.
template <class Error>
double l2_norm_of(const Mesh& mesh, Error&& error) {
  const auto& rule = tet_quadrature_degree5();
  double sum = 0;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    double e2 = 0;
    for (const auto& q : rule) {
      const double e = error(v, q);
      e2 += q.weight * e * e;
    }
    sum += std::abs(tet_volume(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]))) * e2;
  }
  return std::sqrt(std::max(sum, 0.0));
}

}  // namespace

std::vector<double> values_at_vertices(const Mesh& mesh, const ScalarFunction& u) {
  std::vector<double> out(mesh.vertex_capacity(), 0.0);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) out[v] = u(mesh.point(v));
  return out;
}

double l2_interpolation_error(const Mesh& mesh, const std::vector<double>& values, const ScalarFunction& exact) {
  check_values(mesh, values, "L2 error");
  return l2_norm_of(mesh, [&](const TetVertices& v, const QuadraturePoint& q) {
    Point p = Point::Zero();
    double uh = 0;
    for (int k = 0; k < 4; ++k) {
      p += q.bary[k] * mesh.point(v[k]);
      uh += q.bary[k] * values[v[k]];
    }
    return exact(p) - uh;
  });
}

double l2_interpolation_error_in_bulk(const Mesh& mesh, const std::vector<double>& values,
                                      const PointsFunction& exact) {
  check_values(mesh, values, "L2 error");
  const auto& rule = tet_quadrature_degree5();
  // The live tets in blocks, each block's quadrature points evaluated in
  // one call (a bounded buffer whatever the mesh's size).
  constexpr std::size_t kTetsPerCall = 4096;
  std::vector<TetId> block;
  std::vector<Point> points;
  double sum = 0;
  const auto flush = [&] {
    if (block.empty()) return;
    points.clear();
    for (TetId t : block)
      for (const auto& q : rule) {
        Point p = Point::Zero();
        for (int k = 0; k < 4; ++k) p += q.bary[k] * mesh.point(mesh.tet(t)[k]);
        points.push_back(p);
      }
    const std::vector<double> u = exact(points);
    if (u.size() != points.size())
      throw InputError(fmt::format("L2 error: the exact field gave {} values at {} points", u.size(), points.size()));
    std::size_t next = 0;
    for (TetId t : block) {
      const auto& v = mesh.tet(t);
      double e2 = 0;
      for (const auto& q : rule) {
        if (!std::isfinite(u[next])) throw InputError("L2 error: the exact field has a value that is not finite");
        double uh = 0;
        for (int k = 0; k < 4; ++k) uh += q.bary[k] * values[v[k]];
        const double e = u[next++] - uh;
        e2 += q.weight * e * e;
      }
      sum += std::abs(tet_volume(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]))) * e2;
    }
    block.clear();
  };
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    block.push_back(t);
    if (block.size() == kTetsPerCall) flush();
  }
  flush();
  return std::sqrt(std::max(sum, 0.0));
}

double l2_difference(const Mesh& mesh, const std::vector<double>& a, const std::vector<double>& b) {
  check_values(mesh, a, "L2 difference");
  check_values(mesh, b, "L2 difference");
  // (a - b) is P1: the degree-2 integrand is exact under the same rule.
  return l2_norm_of(mesh, [&](const TetVertices& v, const QuadraturePoint& q) {
    double e = 0;
    for (int k = 0; k < 4; ++k) e += q.bary[k] * (a[v[k]] - b[v[k]]);
    return e;
  });
}

}  // namespace metrica
