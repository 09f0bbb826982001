// Moving tets between ranks: each tet goes to the rank chosen for it with
// its vertices (coordinates, metric, global id); the triangles follow the
// tets whose faces they are, and every face whose two tets end on
// different ranks is listed on both as shared, with the rank across.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>

#include <vector>

namespace metrica::distributed {

// The new part of this rank; dest[t] is local tet t's rank. Throws (on
// every rank) for a triangle that is no tet's face or a face of three tets.
Part migrate(const Comm& comm, const Part& part, const std::vector<int>& dest);

// Moves tets until no part's boundary is pinched: a part whose tets
// around a boundary vertex or edge fall into several pieces joined only
// there (a cut rarely avoids all) gives its smaller pieces to a rank
// across them. The adaptation of a part needs a manifold boundary.
// Returns the rounds it took; throws after `max_rounds`.
int make_parts_manifold(const Comm& comm, Part& part, int max_rounds = 30);

}  // namespace metrica::distributed
