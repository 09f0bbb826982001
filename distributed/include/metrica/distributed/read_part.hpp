// Reading a mesh (and its metric) spread over the ranks: rank r reads the
// r-th slice of each binary keyword (`Vertices`, `Tetrahedra`, `Triangles`,
// `SolAtVertices`) at the offsets the file's keyword chain gives, then
// fetches the vertices its tets name from the ranks that read them. No
// rank holds the whole file. Other inputs (ASCII .mesh, .msh, a file in
// the other byte order) are read by rank 0 and sent out in slices.
#pragma once

#include <metrica/classification.hpp>
#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>
#include <metrica/geometry/association.hpp>

#include <functional>
#include <span>
#include <string>

namespace metrica::distributed {

struct ReadCounts {
  std::int64_t vertices = 0, tets = 0, triangles = 0;
  // Keywords of the input the distributed run does not carry (their names).
  std::vector<std::string> dropped;
};

// A boundary vertex's CAD entity and parameters from its point, the
// input's triangles around it (FanSide: each triangle's two edges at the
// vertex, with its surface id) and the input's association records of it
// (VerticesOnGeometricVertices and Triangles); throws InputError when it
// has none.
using AssociateVertex = std::function<GeoParam(GlobalId, const Point&, std::span<FanSide>, const VertexRecords&)>;

// The rank's first part (the tets of its slice, their vertices with their
// metric when `metric_path` is not empty, the triangles of its slice).
// With `associate`, each vertex's CAD parameters too (Part::geo): the
// rank that read a vertex gathers the triangles and the input's records
// at it and asks `associate`. Throws on every rank when the input cannot be read on one.
Part read_part(const Comm& comm, const std::string& mesh_path, const std::string& metric_path, ReadCounts& counts,
               const AssociateVertex& associate = {});

}  // namespace metrica::distributed
