// The cut of a distributed mesh into parts: the dual graph (an edge per
// inner face, from neighbours.hpp; a node per tet, or per cluster of up
// to 32 face-neighbours past 50k tets per rank) cut by PT-Scotch
// (SCOTCH_dgraphPart), then smoothed.
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

// The rank each local tet goes to: `parts` parts (1 .. the ranks). Fewer
// parts than ranks go to ranks 0 .. parts - 1 and the others wait this
// round; as many parts as ranks go each to the rank holding most of its
// tets already. Throws (on every rank) when the graph exceeds
// PT-Scotch's integers.
std::vector<int> partition(const Comm& comm, const Part& part, const TetNeighbours& nb, const PartitionWeights& weights,
                           int parts);

}  // namespace metrica::distributed
