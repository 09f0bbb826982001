#include <metrica/distributed/partition.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <limits>
// ptscotch.h needs <mpi.h>, <stdio.h> and <stdint.h> first.
#include <ptscotch.h>

namespace metrica::distributed {

std::vector<int> partition(const Comm& comm, const Part& part, const TetNeighbours& nb, const PartitionWeights& weights,
                           int parts_wanted) {
  const auto n = std::size_t(comm.size());
  if (parts_wanted <= 1) return std::vector<int>(part.tets.size(), 0);
  const auto local = std::int64_t(part.tets.size());
  const std::int64_t total = comm.sum(local);
  if (total > std::numeric_limits<SCOTCH_Num>::max() / 8)
    throw InputError(fmt::format("{} tets: the partitioner's {}-bit graph ids cannot number their faces", total,
                                 8 * sizeof(SCOTCH_Num)));

  // The rank's slice of the dual graph in PT-Scotch's compressed rows: the
  // faces of the tets touching a vertex to avoid weigh `heavy`, on both
  // sides of a face between ranks alike.
  std::vector<std::int32_t> heavy(part.tets.size(), 0);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (GlobalId g : part.tets[t])
      heavy[t] |= std::binary_search(weights.avoid.begin(), weights.avoid.end(), g) ? 1 : 0;
  const auto heavy_across = values_across(comm, nb, heavy);
  const std::size_t count = part.tets.size();
  std::vector<SCOTCH_Num> vert(count + 1, 0), edges, edge_weights, vert_weights(count), parts(count, 0);
  for (std::size_t t = 0; t < count; ++t)
    for (auto u : nb.local[t]) vert[t + 1] += u >= 0;
  for (const auto& r : nb.remote) ++vert[r.tet + 1];
  for (std::size_t t = 0; t < count; ++t) vert[t + 1] += vert[t];
  edges.resize(std::size_t(vert[count]));
  edge_weights.resize(edges.size());
  {
    std::vector<SCOTCH_Num> at(vert.begin(), vert.end() - 1);
    const auto add = [&](std::size_t t, GlobalId other, bool heavy_edge) {
      const auto e = std::size_t(at[t]++);
      edges[e] = SCOTCH_Num(other);
      edge_weights[e] = heavy_edge ? weights.heavy : 1;
    };
    for (std::size_t t = 0; t < count; ++t)
      for (auto u : nb.local[t])
        if (u >= 0) add(t, nb.first + u, heavy[t] || heavy[std::size_t(u)]);
    for (std::size_t i = 0; i < nb.remote.size(); ++i)
      add(nb.remote[i].tet, nb.remote[i].other, heavy[nb.remote[i].tet] || heavy_across[i]);
  }
  for (std::size_t t = 0; t < count; ++t) vert_weights[t] = std::max<std::int32_t>(1, weights.tets[t]);

  // A context of its own, deterministic with a fixed seed: the same cut
  // for the same graph on the same number of ranks, run after run.
  int failed = 0;
  SCOTCH_Context context;
  SCOTCH_Dgraph graph, bound;
  SCOTCH_Strat strat;
  failed |= SCOTCH_contextInit(&context);
  failed |= SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1);
  failed |= SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1);
  failed |= SCOTCH_contextRandomClone(&context);
  SCOTCH_contextRandomSeed(&context, 1);
  failed |= SCOTCH_dgraphInit(&graph, comm.get());
  SCOTCH_stratInit(&strat);
  if (!failed) {
    const auto m = SCOTCH_Num(edges.size());
    // An empty slice passes valid pointers too, each its own: PT-Scotch
    // takes weights at the address of the ids for no weights, and every
    // rank must say alike whether there are weights.
    SCOTCH_Num dummy[3] = {0, 0, 0};
    failed |= SCOTCH_dgraphBuild(&graph, 0, SCOTCH_Num(local), SCOTCH_Num(local), vert.data(), nullptr,
                                 local ? vert_weights.data() : &dummy[0], nullptr, m, m, m ? edges.data() : &dummy[1],
                                 nullptr, m ? edge_weights.data() : &dummy[2]);
    failed |= SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATBALANCE, SCOTCH_Num(n), SCOTCH_Num(parts_wanted), 0.03);
    if (!failed) failed |= SCOTCH_contextBindDgraph(&context, &graph, &bound);
    if (!failed) {
      failed |= SCOTCH_dgraphPart(&bound, SCOTCH_Num(parts_wanted), &strat, local ? parts.data() : &dummy[0]);
      SCOTCH_dgraphExit(&bound);
    }
  }
  SCOTCH_stratExit(&strat);
  SCOTCH_dgraphExit(&graph);
  SCOTCH_contextExit(&context);
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, comm.get());
  if (any) {
    comm.step([&] {
      if (failed) throw std::runtime_error("PT-Scotch could not partition the dual graph");
    });
  }
  return {parts.begin(), parts.end()};
}

}  // namespace metrica::distributed
