// The unique edges of a mesh, for loops over edges (gradation, quality
// reports, point creation by edges). A snapshot, sorted by (low, high) id.
#pragma once

#include <metrica/mesh.hpp>

#include <vector>

namespace metrica {

std::vector<EdgeVertices> unique_edges(const Mesh& mesh);
// The same edges, ordered by lower vertex only (cheaper: no sort); for
// consumers whose result does not depend on the order.
std::vector<EdgeVertices> unique_edges_unordered(const Mesh& mesh);

}  // namespace metrica
