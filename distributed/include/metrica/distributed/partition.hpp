// The cut of a distributed mesh into parts: the dual graph (a node per
// tet, an edge per inner face) built by pairing each face's tets at the
// rank its key hashes to, then cut by PT-Scotch (SCOTCH_dgraphPart).
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>

#include <cstdint>
#include <vector>

namespace metrica::distributed {

struct PartitionWeights {
  // Per local tet, what it will weigh once adapted (at least 1).
  std::vector<std::int32_t> tets;
  // Vertices the cut should stay away from (sorted global ids): the graph
  // edges of the tets touching them weigh `heavy`, so that the cut passes
  // at least a layer of tets away (the faces the last round kept, with
  // the poor tets the adaptation had to leave against them).
  std::vector<GlobalId> avoid;
  std::int32_t heavy = 100;
};

// The rank each local tet goes to: `parts` parts (1 .. the ranks), on
// ranks 0 .. parts - 1; the others wait this round. Throws (on every
// rank) when a face has more than two tets.
std::vector<int> partition(const Comm& comm, const Part& part, const PartitionWeights& weights, int parts);

}  // namespace metrica::distributed
