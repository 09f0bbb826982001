// The unique edges of a mesh, for loops over edges (gradation, quality
// reports, point creation by edges). A snapshot, sorted by (low, high) id.
#pragma once

#include <metrica/mesh.hpp>

#include <vector>

namespace metrica {

std::vector<EdgeVertices> unique_edges(const Mesh& mesh);
// (The operators' passes build their edge lists on their policy's threads:
// operators/edge_buckets.hpp.)

}  // namespace metrica
