// The geometry policy: where boundary vertices live.
//
// Every operation holds a Geometry, beside the Space, Precision and
// Concurrency policies; those that create, move or remove boundary
// vertices (split and centroid insertion on the boundary, collapse,
// boundary 2-2 flips, smoothing, projection) ask it, and only through
// this concept, the questions that depend on the model:
//
//   boundary_vertex(mesh, parents, weights, surface)
//       the entity and parameters of a new boundary vertex made from
//       `parents` with `weights` (on the ridge the parents share when
//       surface == 0, else on that surface): GeoParam, invalid when the
//       geometry keeps vertices where the operation puts them;
//   point(param)          the point of the model at those parameters;
//   facet_fits(mesh, p, q, r, surface, old_normal, tolerance)
//       may a reconnection leave boundary facet pqr on `surface` where
//       facets of normal `old_normal` were (2-2 flip, collapse)?
//   facet_deviation(mesh, p, q, r, surface)
//       how far facet pqr turns from the surface (0: along it);
//   places(mesh, v)       is boundary vertex v's place the model's (its
//                         moves follow the model, and it belongs on it)?
//
// `on_model()` is for pipelines, not operations: whether the stages that
// only a model gives work to (projection, boundary swap) belong in the
// pipeline; a constant of the type (NoGeometry, CadGeometry) or of the
// object (ModelOrFacets).
//
// NoGeometry keeps the first faceting: new vertices stay where the
// operation puts them, and a boundary facet must keep the plane of the
// facets it replaces (normal deviation below `tolerance`). CadGeometry
// (cad_geometry.hpp) evaluates a CAD model through gmsh. ModelOrFacets
// (model_or_facets.hpp) is either, chosen at run time: the operations'
// and the pipeline's default, the one the library compiles.
#pragma once

#include <metrica/mesh.hpp>

#include <concepts>
#include <span>
#include <string_view>

namespace metrica {

template <class G>
concept Geometry = requires(const G& g, const Mesh& mesh, std::span<const VertexId> parents,
                            std::span<const double> weights, SurfaceId surface, const GeoParam& param,
                            const Eigen::Vector3d& normal) {
  { g.on_model() } -> std::convertible_to<bool>;
  { g.boundary_vertex(mesh, parents, weights, surface) } -> std::same_as<GeoParam>;
  { g.point(param) } -> std::same_as<Point>;
  { g.facet_fits(mesh, VertexId{}, VertexId{}, VertexId{}, surface, normal, 0.0) } -> std::same_as<bool>;
  { g.facet_deviation(mesh, VertexId{}, VertexId{}, VertexId{}, surface) } -> std::same_as<double>;
  { g.places(mesh, VertexId{}) } -> std::same_as<bool>;
};

struct NoGeometry {
  static constexpr bool on_model() { return false; }
  static constexpr std::string_view name = "none";
  GeoParam boundary_vertex(const Mesh&, std::span<const VertexId>, std::span<const double>, SurfaceId) const {
    return {};
  }
  Point point(const GeoParam&) const { return Point::Zero(); }
  bool facet_fits(const Mesh& mesh, VertexId p, VertexId q, VertexId r, SurfaceId, const Eigen::Vector3d& old_normal,
                  double tolerance) const {
    return normal_deviation(face_normal(mesh, p, q, r), old_normal) <= tolerance;
  }
  double facet_deviation(const Mesh&, VertexId, VertexId, VertexId, SurfaceId) const { return 0.0; }
  bool places(const Mesh&, VertexId) const { return false; }
};
static_assert(Geometry<NoGeometry>);

}  // namespace metrica
