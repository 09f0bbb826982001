// The tets of a part that its adaptation may change. A part cut out of a
// mesh may touch itself at a vertex or an edge, or pass around a vertex,
// where the boundary is not a manifold, which a Mesh cannot hold; the tets
// around each such vertex or edge are kept out of this round (their faces
// become kept faces, as those between parts) until what is left has a
// manifold boundary. Local: no rank waits for another.
#pragma once

#include <metrica/distributed/part.hpp>

#include <vector>

namespace metrica::distributed {

// True for the tets adapted this round: those of `wanted` (all when
// empty) less those around a pinch of what they make.
std::vector<bool> adaptable_tets(const Part& part, std::vector<bool> wanted = {});

// The tets within `layers` edge steps of the vertices `near` (sorted
// global ids): a tet with a vertex at fewer steps. The later rounds of an
// adaptation adapt only there, around what the round before left
// unfinished.
std::vector<bool> tets_near(const Part& part, const std::vector<GlobalId>& near, int layers);

}  // namespace metrica::distributed
