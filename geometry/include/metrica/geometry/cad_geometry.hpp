// CadGeometry: the Geometry policy (model.hpp) on a CAD model. A new
// boundary vertex takes the parameters of its parents, interpolated with
// the operation's weights (seam-aware on periodic surfaces, and
// degenerate-aware: at a cone's apex u is free and takes the others'),
// and its point is the model's there. A boundary facet fits when its
// normal deviates from the model's normal at its centroid (parameters
// interpolated) by no more than max_deviation (1 - |cos|), the planar
// tolerance the operation asks, or the deviation of the facets it
// replaces, whichever is largest.
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/geometry/model.hpp>

#include <cmath>
#include <numbers>

namespace metrica {

struct CadGeometry {
  static constexpr bool on_model() { return true; }
  static constexpr std::string_view name = "cad";
  const CadModel* model = nullptr;
  // 1 - cos 8 degrees.
  double max_deviation = 1.0 - std::cos(8.0 * std::numbers::pi / 180.0);

  GeoParam boundary_vertex(const Mesh& mesh, std::span<const VertexId> parents, std::span<const double> weights,
                           SurfaceId surface) const;
  Point point(const GeoParam& g) const { return model->value(g); }
  bool facet_fits(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface,
                  const Eigen::Vector3d& old_normal, double tolerance) const;
  // 1 - |cos| between the facet's normal and the model's at its centroid
  // (0 when its vertices have no parameters).
  double facet_deviation(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface) const;
  // Every boundary vertex is the model's (one it cannot place, having no
  // parameters, stays where it is).
  bool places(const Mesh&, VertexId) const { return true; }
};
static_assert(Geometry<CadGeometry>);

}  // namespace metrica
