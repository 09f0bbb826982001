// Writing a distributed mesh into one binary .meshb: vertices numbered
// globally (a vertex held by several parts is written by the lowest rank
// holding it), each rank's rows placed at offsets from exclusive scans,
// written with MPI-IO into a temporary file that rank 0 renames once every
// rank has written its share. No rank gathers the mesh.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>
#include <metrica/geometry/cad_model.hpp>

#include <string>

namespace metrica::distributed {

struct WrittenCounts {
  std::int64_t vertices = 0, triangles = 0, tets = 0;
  int version = 2;
};

// `version` 0 chooses: 2, or 3 past 2 GB, or 4 past 2^31 - 1 rows. With
// a model, the vertices' CAD association too (VerticesOnGeometric*, as
// the single process writes them).
WrittenCounts write_part(const Comm& comm, const Part& part, const std::string& path, int version = 0,
                         const CadModel* model = nullptr);

}  // namespace metrica::distributed
