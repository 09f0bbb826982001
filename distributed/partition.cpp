#include <metrica/distributed/partition.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>
// ptscotch.h needs <mpi.h>, <stdio.h> and <stdint.h> first.
#include <ptscotch.h>

namespace metrica::distributed {

namespace {

// Tets per graph node: one node per tet up to this many tets per rank,
// then clusters of up to kMaxClusterSize tets.
constexpr std::int64_t kTetsPerNode = 50'000, kMaxClusterSize = 32;

// A cut between clusters is ragged: tets with most of their faces on
// another part (a cluster's tip, a lone small cluster) go there, in
// kSmoothingPasses passes that each decide from the last one's parts.
// A ragged cut touches itself at vertices and edges, whose tets the next
// round keeps out (pinches.hpp; 4.3M tets on 4 ranks, rounds 2 and 3:
// 18.7k and 39.6k tets kept out unsmoothed, 1.9k and 4.6k smoothed).
constexpr int kSmoothingPasses = 2;
void smooth_cut(const Comm& comm, const TetNeighbours& nb, std::vector<int>& dest) {
  for (int pass = 0; pass < kSmoothingPasses; ++pass) {
    const auto across = values_across(comm, nb, dest);
    std::vector<int> next = dest;
    for (std::size_t t = 0; t < dest.size(); ++t) {
      int part[4], faces = 0;
      for (auto u : nb.local[t])
        if (u >= 0) part[faces++] = dest[std::size_t(u)];
      const auto [lo, hi] = remote_faces(nb, std::uint32_t(t));
      for (auto i = lo; i < hi && faces < 4; ++i) part[faces++] = across[i];
      int own = 0;
      for (int i = 0; i < faces; ++i) own += part[i] == dest[t];
      if (own > 1) continue;
      for (int i = 0; i < faces; ++i) {
        int same = 0;
        for (int j = 0; j < faces; ++j) same += part[j] == part[i];
        if (part[i] != dest[t] && same > own + 1) {
          next[t] = part[i];
          break;
        }
      }
    }
    dest.swap(next);
  }
}

}  // namespace

std::vector<int> partition(const Comm& comm, const Part& part, const TetNeighbours& nb, const PartitionWeights& weights,
                           int parts_wanted) {
  const auto n = std::size_t(comm.size());
  if (parts_wanted <= 1) return std::vector<int>(part.tets.size(), 0);
  const std::int64_t total = comm.sum(std::int64_t(part.tets.size()));
  // Clusters of about `size` face-neighbours (grown breadth first within
  // the part) are the graph's nodes: a graph a few times smaller than the
  // mesh costs PT-Scotch that much less memory and time, and parts of
  // millions of tets do not need a finer cut.
  const auto size = std::size_t(std::clamp<std::int64_t>(total / (std::int64_t(n) * kTetsPerNode), 1, kMaxClusterSize));
  const std::size_t count = part.tets.size();
  std::vector<std::int32_t> cluster(count, -1);
  std::vector<std::uint32_t> order, starts;  // tets by cluster; cluster c is order[starts[c] .. starts[c + 1])
  order.reserve(count);
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (cluster[seed] >= 0) continue;
    const auto c = std::int32_t(starts.size());
    starts.push_back(std::uint32_t(order.size()));
    cluster[seed] = c;
    order.push_back(std::uint32_t(seed));
    for (std::size_t head = starts.back(); head < order.size() && order.size() - starts.back() < size; ++head)
      for (auto u : nb.local[order[head]])
        if (u >= 0 && cluster[std::size_t(u)] < 0 && order.size() - starts.back() < size) {
          cluster[std::size_t(u)] = c;
          order.push_back(std::uint32_t(u));
        }
  }
  const auto local = std::int64_t(starts.size());
  starts.push_back(std::uint32_t(order.size()));
  const std::int64_t nodes = comm.sum(local), first = comm.exclusive_scan(local);
  if (nodes > std::numeric_limits<SCOTCH_Num>::max() / 8)
    throw InputError(fmt::format("{} graph nodes: more than the partitioner's {}-bit ids can number", nodes,
                                 8 * sizeof(SCOTCH_Num)));

  // The rank's slice of the graph in PT-Scotch's compressed rows: a face
  // between clusters adds 1 to their edge, `heavy` when one of its tets
  // touches a vertex to avoid (the same on both sides of a face between
  // ranks).
  // Per tet, only while the values across are fetched (4 bytes a tet
  // each: this step sets a rank's peak at 4.3M tets on 4 ranks).
  std::vector<bool> heavy(count, false);
  std::vector<std::int32_t> heavy_across, cluster_across;
  {
    std::vector<bool> avoided(part.vertex_ids.size());
    for (std::size_t v = 0; v < avoided.size(); ++v)
      avoided[v] = std::binary_search(weights.avoid.begin(), weights.avoid.end(), part.vertex_ids[v]);
    std::vector<std::int32_t> values(count);
    for (std::size_t t = 0; t < count; ++t) {
      for (auto v : part.tets[t]) heavy[t] = heavy[t] || avoided[v];
      values[t] = heavy[t];
    }
    heavy_across = values_across(comm, nb, values);
    for (std::size_t t = 0; t < count; ++t) values[t] = std::int32_t(first + cluster[t]);
    cluster_across = values_across(comm, nb, values);
  }
  std::vector<SCOTCH_Num> vert(std::size_t(local) + 1, 0), edges, edge_weights, vert_weights(std::size_t(local), 0),
      parts(std::size_t(local), 0);
  {
    std::vector<std::pair<SCOTCH_Num, SCOTCH_Num>> row;  // (node across, weight) in the order met
    const auto add = [&](SCOTCH_Num other, bool heavy_edge) {
      const SCOTCH_Num w = heavy_edge ? weights.heavy : 1;
      for (auto& [o, ow] : row)
        if (o == other) {
          ow += w;
          return;
        }
      row.emplace_back(other, w);
    };
    for (std::size_t c = 0; c < std::size_t(local); ++c) {
      row.clear();
      for (auto k = starts[c]; k < starts[c + 1]; ++k) {
        const auto t = order[k];
        vert_weights[c] += std::max<std::int32_t>(1, weights.tets[t]);
        for (auto u : nb.local[t])
          if (u >= 0 && cluster[std::size_t(u)] != std::int32_t(c))
            add(SCOTCH_Num(first + cluster[std::size_t(u)]), heavy[t] || heavy[std::size_t(u)]);
        const auto [lo, hi] = remote_faces(nb, t);
        for (auto i = lo; i < hi; ++i) {
          add(cluster_across[i], heavy[t] || heavy_across[i]);
        }
      }
      for (const auto& [o, w] : row) edges.push_back(o), edge_weights.push_back(w);
      vert[c + 1] = SCOTCH_Num(edges.size());
    }
  }

  std::int64_t weight = 0;
  for (auto w : vert_weights) weight += w;
  const std::int64_t total_weight = comm.sum(weight);
  if (total_weight > std::numeric_limits<SCOTCH_Num>::max() / 2)
    throw InputError(fmt::format("tets weighing {} in all: more than the partitioner's {}-bit weights can sum",
                                 total_weight, 8 * sizeof(SCOTCH_Num)));

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
  std::vector<int> dest(count);
  for (std::size_t t = 0; t < count; ++t) dest[t] = int(parts[std::size_t(cluster[t])]);
  if (size > 1) smooth_cut(comm, nb, dest);
  // PT-Scotch numbers its parts freely: each part goes to the rank that
  // holds most of its tets already, so that a later round moves few.
  if (std::size_t(parts_wanted) == n) {
    std::vector<std::int64_t> here(n, 0), all(n * n);
    for (int d : dest) ++here[std::size_t(d)];
    MPI_Allgather(here.data(), int(n), MPI_INT64_T, all.data(), int(n), MPI_INT64_T, comm.get());
    std::vector<std::size_t> pairs(n * n);  // (rank, part) pairs, most tets first
    std::iota(pairs.begin(), pairs.end(), std::size_t{0});
    std::stable_sort(pairs.begin(), pairs.end(), [&](std::size_t a, std::size_t b) { return all[a] > all[b]; });
    std::vector<int> rank_of(n, -1);
    std::vector<bool> taken(n, false);
    for (auto i : pairs) {
      const auto r = i / n, p = i % n;
      if (taken[r] || rank_of[p] >= 0) continue;
      taken[r] = true;
      rank_of[p] = int(r);
    }
    for (auto& d : dest) d = rank_of[std::size_t(d)];
  }
  return dest;
}

}  // namespace metrica::distributed
