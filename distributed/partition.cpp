#include <metrica/distributed/partition.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <limits>
// ptscotch.h needs <mpi.h>, <stdio.h> and <stdint.h> first.
#include <ptscotch.h>

namespace metrica::distributed {

namespace {

struct FaceOfTet {
  FaceKey key;
  GlobalId tet;
  std::int32_t heavy;
  std::int32_t pad = 0;
};
struct Neighbour {
  GlobalId tet, other;
  std::int32_t weight;
  std::int32_t pad = 0;
};

// Faces per rank in one batch of the rendezvous (40 bytes each, sent and
// received).
constexpr std::int64_t kFacesPerBatch = 1 << 20;

}  // namespace

std::vector<int> partition(const Comm& comm, const Part& part, const PartitionWeights& weights, int parts_wanted) {
  const auto n = std::size_t(comm.size());
  if (parts_wanted <= 1) return std::vector<int>(part.tets.size(), 0);
  const auto local = std::int64_t(part.tets.size());
  const std::int64_t total = comm.sum(local);
  if (total > std::numeric_limits<SCOTCH_Num>::max() / 8)
    throw InputError(fmt::format("{} tets: the partitioner's {}-bit graph ids cannot number their faces", total,
                                 8 * sizeof(SCOTCH_Num)));
  const std::int64_t first = comm.exclusive_scan(local);
  std::vector<std::int64_t> starts(n + 1);
  MPI_Allgather(&first, 1, MPI_INT64_T, starts.data(), 1, MPI_INT64_T, comm.get());
  starts[n] = total;

  // Each face to the rank that pairs its tets, in batches of faces (by
  // their hash, so that a face's two tets meet in the same batch): the
  // records sent and received were the peak of a rank's memory in the
  // rounds after the first, and batches bound them.
  std::vector<bool> heavy(part.tets.size(), false);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (GlobalId g : part.tets[t])
      heavy[t] = heavy[t] || std::binary_search(weights.avoid.begin(), weights.avoid.end(), g);
  const std::int64_t batches = std::max<std::int64_t>(1, (4 * comm.max(local) + kFacesPerBatch - 1) / kFacesPerBatch);
  const auto rank_of = [&](GlobalId t) {
    return std::size_t(std::upper_bound(starts.begin(), starts.end(), t) - starts.begin() - 1);
  };
  std::vector<Neighbour> nb;
  for (std::int64_t batch = 0; batch < batches; ++batch) {
    std::vector<std::vector<FaceOfTet>> out(n);
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      const auto& v = part.tets[t];
      for (const auto& f : kTetFaces) {
        const FaceKey key = face_key(v[f[0]], v[f[1]], v[f[2]]);
        const std::uint64_t h = face_hash(key);
        if (std::int64_t((h / n) % std::uint64_t(batches)) != batch) continue;
        out[h % n].push_back({key, first + GlobalId(t), heavy[t] ? 1 : 0});
      }
    }
    auto faces = comm.exchange(out);
    out = {};
    std::vector<std::vector<Neighbour>> pairs(n);
    comm.step([&] {
      std::sort(faces.begin(), faces.end(),
                [](const FaceOfTet& a, const FaceOfTet& b) { return a.key != b.key ? a.key < b.key : a.tet < b.tet; });
      for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].key == faces[i].key) ++j;
        if (j - i > 2)
          throw InputError(fmt::format("the face ({} {} {}) has {} tets (at most 2)", faces[i].key[0] + 1,
                                       faces[i].key[1] + 1, faces[i].key[2] + 1, j - i));
        if (j - i == 2) {
          const std::int32_t w = (faces[i].heavy || faces[i + 1].heavy) ? weights.heavy : 1;
          pairs[rank_of(faces[i].tet)].push_back({faces[i].tet, faces[i + 1].tet, w});
          pairs[rank_of(faces[i + 1].tet)].push_back({faces[i + 1].tet, faces[i].tet, w});
        }
        i = j;
      }
    });
    faces = {};
    const auto got = comm.exchange(pairs);
    nb.insert(nb.end(), got.begin(), got.end());
  }
  std::sort(nb.begin(), nb.end(),
            [](const Neighbour& a, const Neighbour& b) { return a.tet != b.tet ? a.tet < b.tet : a.other < b.other; });

  // The rank's slice of the graph in PT-Scotch's compressed rows.
  const std::size_t count = part.tets.size();
  std::vector<SCOTCH_Num> vert(count + 1, 0), edges, edge_weights, vert_weights(count), parts(count, 0);
  for (const auto& e : nb) ++vert[std::size_t(e.tet - first) + 1];
  for (std::size_t t = 0; t < count; ++t) vert[t + 1] += vert[t];
  for (const auto& e : nb) edges.push_back(SCOTCH_Num(e.other)), edge_weights.push_back(e.weight);
  for (std::size_t t = 0; t < count; ++t) vert_weights[t] = std::max<std::int32_t>(1, weights.tets[t]);
  nb = {};

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
