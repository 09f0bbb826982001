// ModelOrFacets: the Geometry policy (model.hpp) chosen at run time, the
// one the compiled pipeline holds: a CAD model's (CadGeometry) when one is
// given, else the start mesh's facets (NoGeometry), each question sent to
// the one in force. One instantiation serves adaptations on a model and
// off one, so the library compiles each (space, concurrency) pair once.
#pragma once

#include <metrica/geometry/cad_geometry.hpp>
#include <metrica/geometry/model.hpp>

namespace metrica {

struct ModelOrFacets {
  static constexpr std::string_view name = "model-or-facets";
  CadGeometry cad;  // cad.model null: the facets

  ModelOrFacets() = default;
  explicit ModelOrFacets(const CadModel* model) : cad{.model = model} {}

  bool on_model() const { return cad.model != nullptr; }
  GeoParam boundary_vertex(const Mesh& mesh, std::span<const VertexId> parents, std::span<const double> weights,
                           SurfaceId surface) const {
    return on_model() ? cad.boundary_vertex(mesh, parents, weights, surface)
                      : NoGeometry{}.boundary_vertex(mesh, parents, weights, surface);
  }
  Point point(const GeoParam& g) const { return on_model() ? cad.point(g) : NoGeometry{}.point(g); }
  bool facet_fits(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface,
                  const Eigen::Vector3d& old_normal, double tolerance) const {
    return on_model() ? cad.facet_fits(mesh, p, q, r, surface, old_normal, tolerance)
                      : NoGeometry{}.facet_fits(mesh, p, q, r, surface, old_normal, tolerance);
  }
  double facet_deviation(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId surface) const {
    return on_model() ? cad.facet_deviation(mesh, p, q, r, surface)
                      : NoGeometry{}.facet_deviation(mesh, p, q, r, surface);
  }
  bool places(const Mesh& mesh, VertexId v) const {
    return on_model() ? cad.places(mesh, v) : NoGeometry{}.places(mesh, v);
  }
};
static_assert(Geometry<ModelOrFacets>);

}  // namespace metrica
