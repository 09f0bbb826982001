// Moving tets between ranks: each tet goes to the rank chosen for it with
// its vertices (coordinates, metric, global id); the triangles follow the
// tets whose faces they are, and every face whose two tets end on
// different ranks is listed on both as shared, with the rank across.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/neighbours.hpp>
#include <metrica/distributed/part.hpp>

#include <vector>

namespace metrica::distributed {

// The new part of this rank, made from `part` in place (what stays stays
// where it is, what leaves goes as records); dest[t] is local tet t's
// rank, nb the part's neighbours (freed once read). Throws (on every rank) for a triangle
// that is no tet's face or a face of three tets.
Part migrate(const Comm& comm, Part part, TetNeighbours nb, const std::vector<int>& dest);

}  // namespace metrica::distributed
