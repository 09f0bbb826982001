// Classification of the boundary: ridges and corners.
//
// A ridge edge lies between boundary faces of two different surface ids,
// or is a feature edge given by the input. A corner is a boundary vertex
// on 3 or more ridge edges, at the end of a ridge (1 ridge edge), where two
// ridges of different surface pairs meet, or one the input requires. Other
// vertices on a ridge are ridge vertices; other boundary vertices are
// surface vertices; the rest are interior.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

#include <cstdint>
#include <span>
#include <unordered_set>
#include <vector>

namespace metrica {

// Internal surfaces (Mesh::internal_surface_id) count as surfaces: their
// vertices are surface, ridge or corner vertices like the outer boundary's,
// with ridges where internal and outer surfaces meet.
struct Classification {
  std::vector<VertexClass> vertex_class;  // by vertex id (dead vertices: interior)
  std::unordered_set<std::uint64_t> ridges;
  std::vector<char> on_internal_surface;  // by vertex id (empty: none)
};

// Computes the classification from surface ids, feature edges and required
// vertices, without changing the mesh (validate() compares it with the
// stored one; Mesh::classify() stores it). The sweep over the tets for
// their surface faces runs on `run`'s parts; the result is the same for
// any number of parts.
Classification compute_classification(const Mesh& mesh, const PartRunner& run = {});

// One boundary vertex's class from the surface faces around it, for a
// vertex of a mesh held in pieces (no feature edges, not required): each
// face at the vertex gives its two edges there, as the edge's other end
// and the face's surface id. The rule of compute_classification. Sorts
// `sides`.
struct FanSide {
  std::int64_t other;
  SurfaceId surface;
  friend auto operator<=>(const FanSide&, const FanSide&) = default;
};
VertexClass vertex_class_of_fan(std::span<FanSide> sides);

// Ridge curves: connected chains of ridge edges between corners (a closed
// ridge loop without corners counts as one curve).
std::size_t count_ridge_curves(const Mesh& mesh);

}  // namespace metrica
