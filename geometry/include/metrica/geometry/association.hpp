// The association of a mesh's boundary vertices with a CAD model: each
// boundary vertex's entity (model vertex, curve, surface) and parameters
// (Mesh::geo_param), what the Geometry policy interpolates from.
//
// The mesh's surface ids are the model's surface tags. Surface vertices
// take the (u, v) of the input's VerticesOnGeometricTriangles records
// when the model's point there is the vertex (within kTrustedRecord of
// the model's size), else their projection: records written with another
// kernel's parameterization of the same model (EGADS's, say) are checked,
// never trusted blindly. Ridge vertices take the nearest curve among
// those of their surfaces, corners the nearest model vertex (matched by
// geometry: other tools number curves and model vertices differently).
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

#include <set>
#include <span>
#include <string>

namespace metrica {

// A record's parameters are the vertex's when the model's point there is
// this close to it, relative to the model's size.
inline constexpr double kTrustedRecord = 1e-8;
// A boundary vertex is on the model when this close to its entity's point
// (`check --geometry`'s default tolerance, and what every output keeps).
inline constexpr double kOnModel = 1e-8;

struct VertexAssociation;

struct AssociationReport {
  std::size_t vertices = 0;   // boundary vertices associated
  std::size_t from_file = 0;  // of which with the input's parameters
  double max_distance = 0.0;  // largest distance from a vertex to its entity's point
  // Vertices whose records name a point of the model farther than
  // kTrustedRecord from them (projected instead), and the farthest.
  std::size_t records_refused = 0;
  double refused_distance = 0.0;
  // Vertices farther than kOnModel from their entity's point (brought onto
  // the model in the adaptation's first stage).
  std::size_t off_model = 0;
  void add(const VertexAssociation& a);
};

// Associates every boundary vertex. Throws InputError when a surface id is
// not a surface of the model, or a vertex is farther than `tolerance`
// (0: 1e-3 of the model's size) from every entity it may lie on.
AssociationReport associate(Mesh& mesh, const CadModel& model, const io::MeshData* input = nullptr,
                            double tolerance = 0.0);

// One boundary vertex's association, for meshes held in pieces: p, the
// surface ids of the faces around it, its class (vertex_class_of_fan)
// and the input's records of it (none: by projection alone).
struct VertexRecords {
  std::span<const io::GeoRecord* const> on_surface;  // its (u, v) on surfaces
  int model_vertex = 0;                              // its model vertex (0: none)
};
struct VertexAssociation {
  GeoParam param;  // invalid when no entity may hold it
  double distance = std::numeric_limits<double>::infinity();
  bool from_file = false;
  // The distance from the vertex to the point its records name, when they
  // name one farther than kTrustedRecord (else -1).
  double refused_record = -1.0;
};
VertexAssociation associate_vertex(const CadModel& model, const Point& p, std::span<const int> surfaces,
                                   VertexClass cls, const VertexRecords& file, double tolerance);
// The InputErrors of associate: vertex v farther than the tolerance from
// every entity it may lie on; surface ids the model does not have.
std::string off_model_message(VertexId v, const Point& p, const VertexAssociation& a, const CadModel& model,
                              double tolerance);
std::string unknown_surfaces_message(const std::set<int>& missing, const CadModel& model);

// How far the boundary vertices are from their entities.
struct ModelDistance {
  std::size_t vertices = 0;      // boundary vertices with an entity
  std::size_t unassociated = 0;  // boundary vertices without one
  double max = 0.0;              // largest distance
  VertexId worst = kNoId;        // where
  std::size_t beyond = 0;        // vertices farther than the tolerance asked
};
// Faces of surface `skip` (a piece's cut) make no boundary vertex.
ModelDistance model_distance(const Mesh& mesh, const CadModel& model, double tolerance = 1e-8, SurfaceId skip = 0);

// The boundary vertices without an entity or farther than `tolerance`
// from it (faces of surface `skip` make no boundary vertex).
std::vector<VertexId> vertices_off_model(const Mesh& mesh, const CadModel& model, double tolerance, SurfaceId skip = 0);

// InputError naming `what` when a boundary vertex has no model entity or
// lies farther than `check --geometry`'s default tolerance (1e-8) from it:
// an output that check would refuse is never written.
void require_on_model(const Mesh& mesh, const CadModel& model, const std::string& what, SurfaceId skip = 0);

// Adds to `data` (whose primary records extract_mesh_data wrote) what
// refine and Feflo.a also read: a model vertex's t on each of its curves,
// and a curve's or model vertex's (u, v) on each adjacent surface.
void complete_geometry_records(io::MeshData& data, const CadModel& model);

}  // namespace metrica
