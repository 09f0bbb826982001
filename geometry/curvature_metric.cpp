#include <metrica/error.hpp>
#include <metrica/geometry/curvature_metric.hpp>
#include <metrica/numbering.hpp>

#include <Eigen/Dense>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace metrica {

std::vector<Sym6> curvature_metric(const Mesh& mesh, const CadModel& model, double angle) {
  if (!(angle > 0.0) || !(angle <= std::numbers::pi / 2))
    throw InputError(fmt::format("curvature metric: the angle must be in (0, 90] degrees (got {} radians)", angle));
  const double floor = 1.0 / (model.size() * model.size());
  std::vector<Eigen::Matrix3d> sum(mesh.vertex_capacity(), floor * Eigen::Matrix3d::Identity());
  // The surfaces around each surface vertex, boundary or internal (once each).
  std::vector<std::vector<int>> surfaces(mesh.vertex_capacity());
  for_each_surface_face(mesh, [&](TetId t, int f) {
    const SurfaceId s = mesh.face_surface_id(t, f);
    for (VertexId v : face_vertices(mesh.tet(t), f)) {
      auto& list = surfaces[v];
      if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
    }
  });
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v) || surfaces[v].empty()) continue;
    if (!mesh.has_geo_params() || !mesh.geo_param(v).valid())
      throw InputError(fmt::format("curvature metric: boundary vertex {} has no model entity", numbered(v)));
    for (int s : surfaces[v]) {
      if (!model.has(2, s)) continue;
      const auto uv = model.on_surface(mesh.geo_param(v), s);
      const CadModel::Curvatures c = model.principal_curvatures(s, uv[0], uv[1]);
      for (const auto& [k, d] : {std::pair{c.max, c.max_direction}, std::pair{c.min, c.min_direction}}) {
        if (!std::isfinite(k) || d.squaredNorm() == 0.0) continue;
        const double l = k / angle;
        sum[v] += l * l * d * d.transpose();
      }
    }
  }
  std::vector<Sym6> out(mesh.vertex_capacity());
  for (std::size_t v = 0; v < out.size(); ++v) {
    const auto& m = sum[v];
    out[v] = {m(0, 0), m(0, 1), m(1, 1), m(0, 2), m(1, 2), m(2, 2)};
  }
  return out;
}

}  // namespace metrica
