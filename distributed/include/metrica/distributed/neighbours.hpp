// The tet across each face of a part's tets: in the part (found through
// the tets around the face's vertices), on another rank (the faces no
// local tet pairs meet at the rank their key hashes to), or none (the
// boundary). Only the faces without a local pair travel, so a round's
// cut and move cost messages in the parts' surfaces, not their volumes.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace metrica::distributed {

// The tets around each local vertex, in compressed rows: those of vertex
// v are around[first[v] .. first[v + 1]).
struct TetsAround {
  std::vector<std::uint32_t> first, around;
  explicit TetsAround(const Part& part);
};

// A face whose tet across lies on another rank.
struct RemoteFace {
  std::uint32_t tet;  // local tet
  std::int32_t face;  // its face (kTetFaces order)
  GlobalId other;     // the tet across, by its global index
  std::int32_t rank;  // the rank holding it
  std::int32_t pad = 0;
};

// Within the part alone: the tet across each face (-1: none here) and
// the faces without one (the boundary and the faces shared with other
// ranks). Throws InputError for a face of three or more tets.
struct LocalNeighbours {
  std::vector<std::array<std::int32_t, 4>> across;
  std::vector<std::pair<std::uint32_t, std::int32_t>> open;  // (tet, face)
};
LocalNeighbours local_neighbours(const Part& part);

struct TetNeighbours {
  GlobalId first = 0;                              // global index of local tet 0 (an exclusive scan of the parts' tets)
  std::vector<std::array<std::int32_t, 4>> local;  // local tet across each face; -1: none here
  std::vector<RemoteFace> remote;                  // sorted by (tet, face)
};

// The places in nb.remote of local tet t's faces between ranks: [first, last).
inline std::pair<std::size_t, std::size_t> remote_faces(const TetNeighbours& nb, std::uint32_t t) {
  const auto below = [](const RemoteFace& r, std::uint32_t x) { return r.tet < x; };
  const auto from = std::lower_bound(nb.remote.begin(), nb.remote.end(), t, below);
  auto to = from;
  while (to != nb.remote.end() && to->tet == t) ++to;
  return {std::size_t(from - nb.remote.begin()), std::size_t(to - nb.remote.begin())};
}

// Every rank calls it. Throws (on every rank) when a face has more than
// two tets.
TetNeighbours neighbours(const Comm& comm, const Part& part);

// For each remote face of `nb`, the value the rank across has for its tet
// (per_tet[t] there). Every rank calls it.
std::vector<std::int32_t> values_across(const Comm& comm, const TetNeighbours& nb,
                                        const std::vector<std::int32_t>& per_tet);

}  // namespace metrica::distributed
