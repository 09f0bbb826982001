// Reading a mesh (and its metric) spread over the ranks: rank r reads the
// r-th slice of each binary keyword (`Vertices`, `Tetrahedra`, `Triangles`,
// `SolAtVertices`) at the offsets the file's keyword chain gives, then
// fetches the vertices its tets name from the ranks that read them. No
// rank holds the whole file. Other inputs (ASCII .mesh, .msh, a file in
// the other byte order) are read by rank 0 and sent out in slices.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>

#include <string>

namespace metrica::distributed {

struct ReadCounts {
  std::int64_t vertices = 0, tets = 0, triangles = 0;
  // Keywords of the input the distributed run does not carry (their names).
  std::vector<std::string> dropped;
};

// The rank's first part (the tets of its slice, their vertices with their
// metric when `metric_path` is not empty, the triangles of its slice).
// Throws on every rank when the input cannot be read on one.
Part read_part(const Comm& comm, const std::string& mesh_path, const std::string& metric_path, ReadCounts& counts);

}  // namespace metrica::distributed
