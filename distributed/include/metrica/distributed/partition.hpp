// The cut of a distributed mesh into parts: the dual graph (a node per
// tet, an edge per inner face, from neighbours.hpp) cut by PT-Scotch
// (SCOTCH_dgraphPart).
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/neighbours.hpp>
#include <metrica/distributed/part.hpp>

#include <cstdint>
#include <vector>

namespace metrica::distributed {

struct PartitionWeights {
  // Per local tet, what it will weigh once adapted (at least 1).
  std::vector<std::int32_t> tets;
  // Vertices the cut should stay away from (sorted global ids): the graph
  // edges of the tets touching them weigh `heavy`, so that the cut passes
  // at least a layer of tets away (what the last round left unfinished).
  std::vector<GlobalId> avoid;
  std::int32_t heavy = 100;
};

// The rank each local tet goes to: `parts` parts (1 .. the ranks), on
// ranks 0 .. parts - 1; the others wait this round. Throws (on every
// rank) when a face has more than two tets.
std::vector<int> partition(const Comm& comm, const Part& part, const TetNeighbours& nb, const PartitionWeights& weights,
                           int parts);

}  // namespace metrica::distributed
