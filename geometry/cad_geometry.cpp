#include <metrica/error.hpp>
#include <metrica/geometry/cad_geometry.hpp>

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <cmath>

namespace metrica {
namespace {

using Curves = boost::container::small_vector<int, 8>;

// The curves a parent may share with the others: its own, or those through
// its model vertex.
Curves curves_of(const CadModel& model, const GeoParam& g) {
  Curves out;
  if (g.dim == 1) out.push_back(g.tag);
  if (g.dim == 0)
    for (int c : model.curves_of_vertex(g.tag)) out.push_back(c);
  return out;
}

}  // namespace

GeoParam CadGeometry::boundary_vertex(const Mesh& mesh, std::span<const VertexId> parents,
                                      std::span<const double> weights, SurfaceId surface) const {
  if (!mesh.has_geo_params()) return {};
  for (VertexId v : parents)
    if (!mesh.geo_param(v).valid()) return {};
  if (surface <= 0) {
    // On the curve all parents lie on.
    Curves shared = curves_of(*model, mesh.geo_param(parents[0]));
    for (std::size_t i = 1; i < parents.size(); ++i) {
      const Curves mine = curves_of(*model, mesh.geo_param(parents[i]));
      shared.erase(std::remove_if(shared.begin(), shared.end(),
                                  [&](int c) { return std::find(mine.begin(), mine.end(), c) == mine.end(); }),
                   shared.end());
    }
    Point straight = Point::Zero();
    for (std::size_t i = 0; i < parents.size(); ++i) straight += weights[i] * mesh.point(parents[i]);
    if (shared.empty()) {
      // No curve in common by the parents' parameters (a vertex at a model
      // vertex recorded on one of its curves only): the nearest of their
      // curves to the straight point, by projection.
      GeoParam best;
      double best_distance = std::numeric_limits<double>::infinity();
      for (VertexId v : parents)
        for (int c : curves_of(*model, mesh.geo_param(v))) {
          try {
            const GeoParam g = model->parametrize(1, c, straight);
            const double d = (model->value(g) - straight).norm();
            if (d < best_distance) {
              best_distance = d;
              best = g;
            }
          } catch (const InputError&) {
          }
        }
      return best;
    }
    GeoParam best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int c : shared) {
      // The reference t: a parent on the curve itself, else the first.
      const double* near = nullptr;
      double t_ref = 0.0;
      for (VertexId v : parents)
        if (mesh.geo_param(v).dim == 1) {
          t_ref = mesh.geo_param(v).u;
          near = &t_ref;
          break;
        }
      double t = 0.0;
      for (std::size_t i = 0; i < parents.size(); ++i)
        t += weights[i] * model->on_curve(mesh.geo_param(parents[i]), c, near);
      const GeoParam g{c, 1, t, 0.0};
      const double d = shared.size() == 1 ? 0.0 : (model->value(g) - straight).norm();
      if (d < best_distance) {
        best_distance = d;
        best = g;
      }
    }
    return best;
  }
  // On the surface: each parent's (u, v) there. At a degenerate point (a
  // cone's apex, a sphere's pole: d/du vanishes) u is free and takes the
  // mean of the other parents'; such a point may be a model vertex or a
  // surface vertex at the border of the parameter range. The reference for
  // the period shift is the first parent on the surface itself that is not
  // degenerate (a pole's u says nothing of where the others are).
  const int s = surface;
  if (!model->has(2, s)) return {};
  const std::size_t n = parents.size();
  boost::container::small_vector<std::array<double, 2>, 4> uv(n);
  for (std::size_t i = 0; i < n; ++i) uv[i] = model->on_surface(mesh.geo_param(parents[i]), s);
  const CadModel::Range& range = model->range(2, s);
  const double tiny = 1e-9 * model->size();
  boost::container::small_vector<std::array<bool, 2>, 4> free(n, {false, false});
  for (std::size_t i = 0; i < n; ++i) {
    if (mesh.geo_param(parents[i]).dim == 2) {
      // Only the border of the range can be degenerate.
      bool border = false;
      for (std::size_t k = 0; k < 2; ++k) {
        const double scale = std::max(1.0, range.hi[k] - range.lo[k]);
        border = border || std::abs(uv[i][k] - range.lo[k]) < 1e-12 * scale ||
                 std::abs(uv[i][k] - range.hi[k]) < 1e-12 * scale;
      }
      if (!border) continue;
    }
    const auto d = model->derivatives(s, uv[i][0], uv[i][1]);
    for (std::size_t k = 0; k < 2; ++k) free[i][k] = d[k].norm() < tiny;
  }
  std::size_t ref = n;
  for (int pass = 0; pass < 2 && ref == n; ++pass)
    for (std::size_t i = 0; i < n; ++i)
      if (mesh.geo_param(parents[i]).dim == 2 && (pass == 1 || (!free[i][0] && !free[i][1]))) {
        ref = i;
        break;
      }
  if (ref == n) ref = 0;
  for (std::size_t k = 0; k < 2; ++k)
    if (range.period[k] > 0.0)
      for (std::size_t i = 0; i < n; ++i)
        uv[i][k] += range.period[k] * std::round((uv[ref][k] - uv[i][k]) / range.period[k]);
  for (std::size_t k = 0; k < 2; ++k) {
    double sum = 0.0;
    int counted = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!free[i][k]) {
        sum += uv[i][k];
        ++counted;
      }
    if (counted == 0) continue;
    for (std::size_t i = 0; i < n; ++i)
      if (free[i][k]) uv[i][k] = sum / counted;
  }
  GeoParam g{s, 2, 0.0, 0.0};
  for (std::size_t i = 0; i < parents.size(); ++i) {
    g.u += weights[i] * uv[i][0];
    g.v += weights[i] * uv[i][1];
  }
  return g;
}

namespace {
// The model's normal at the centroid of facet pqr (parameters interpolated
// from its vertices), or zero when they have none.
Eigen::Vector3d model_normal_at_centroid(const CadGeometry& g, const Mesh& mesh, VertexId p, VertexId q, VertexId r,
                                         SurfaceId surface) {
  const std::array<VertexId, 3> corners{p, q, r};
  const std::array<double, 3> third{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
  const GeoParam c = g.boundary_vertex(mesh, corners, third, surface);
  if (!c.valid()) return Eigen::Vector3d::Zero();
  return g.model->normal(surface, c.u, c.v);
}
}  // namespace

bool CadGeometry::facet_fits(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface,
                             const Eigen::Vector3d& old_normal, double tolerance) const {
  const Eigen::Vector3d n = face_normal(mesh, p, q, r);
  const Eigen::Vector3d model_normal = model_normal_at_centroid(*this, mesh, p, q, r, surface);
  if (model_normal.squaredNorm() == 0.0) return normal_deviation(n, old_normal) <= tolerance;
  // Within the bound, or no farther from the model than the facets it
  // replaces (thin facets near a ridge deviate whichever way they turn).
  const double bound = std::max({tolerance, max_deviation, normal_deviation(old_normal, model_normal)});
  return normal_deviation(n, model_normal) <= bound;
}

double CadGeometry::facet_deviation(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface) const {
  const Eigen::Vector3d model_normal = model_normal_at_centroid(*this, mesh, p, q, r, surface);
  if (model_normal.squaredNorm() == 0.0) return 0.0;
  return normal_deviation(face_normal(mesh, p, q, r), model_normal);
}

}  // namespace metrica
