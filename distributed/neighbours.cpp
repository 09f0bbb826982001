#include <metrica/distributed/neighbours.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

namespace metrica::distributed {

namespace {

// A face no local tet pairs, at the rank that pairs it.
struct OpenFace {
  FaceKey key;
  GlobalId tet;
  std::int32_t face, rank;
};

// Back to the rank of `tet`: the tet across its face.
struct Paired {
  GlobalId tet, other;
  std::int32_t face, rank;
};

// A tet's value, to the rank holding `to` across a face of tet `from`.
struct ValueAcross {
  GlobalId to, from;
  std::int32_t value, pad = 0;
};

[[noreturn]] void too_many(const FaceKey& k, std::size_t tets) {
  throw InputError(fmt::format("the face ({} {} {}) has {} tets (at most 2)", k[0] + 1, k[1] + 1, k[2] + 1, tets));
}

}  // namespace

TetsAround::TetsAround(const Part& part, const VertexIndex& index) : first(part.vertex_ids.size() + 1, 0) {
  // The tets in local numbers while the rows are made (freed on return).
  std::vector<std::array<std::uint32_t, 4>> local(part.tets.size());
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (int c = 0; c < 4; ++c) {
      local[t][std::size_t(c)] = std::uint32_t(index.find(part.tets[t][std::size_t(c)]));
      ++first[local[t][std::size_t(c)] + 1];
    }
  for (std::size_t v = 0; v + 1 < first.size(); ++v) first[v + 1] += first[v];
  around.resize(first.back());
  auto fill = first;
  for (std::size_t t = 0; t < local.size(); ++t)
    for (auto v : local[t]) around[fill[v]++] = std::uint32_t(t);
}

LocalNeighbours local_neighbours(const Part& part, const VertexIndex& index) {
  LocalNeighbours nb;
  const std::size_t nt = part.tets.size();
  // The tets around each vertex; the part's own global ids are compared
  // below (a copy of the tets in local numbers beside the rows and the
  // result would cost 16 bytes a tet at the rounds' peak).
  const TetsAround rows(part, index);
  const auto& first = rows.first;
  const auto& around = rows.around;
  const auto local = [&](GlobalId g) { return std::uint32_t(index.find(g)); };
  nb.across.assign(nt, {-1, -1, -1, -1});
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& v = part.tets[t];
    if (nb.across[t][0] >= 0 && nb.across[t][1] >= 0 && nb.across[t][2] >= 0 && nb.across[t][3] >= 0) continue;
    const std::uint32_t lv[4] = {local(v[0]), local(v[1]), local(v[2]), local(v[3])};
    for (int f = 0; f < 4; ++f) {
      if (nb.across[t][std::size_t(f)] >= 0) continue;
      const auto& c = kTetFaces[f];
      const GlobalId a = v[std::size_t(c[0])], b = v[std::size_t(c[1])], d = v[std::size_t(c[2])];
      // The other tets holding the face: among those around its vertex
      // with the fewest.
      std::uint32_t pick = lv[c[0]];
      for (int e : {c[1], c[2]})
        if (first[lv[e] + 1] - first[lv[e]] < first[pick + 1] - first[pick]) pick = lv[e];
      int found = 0;
      std::uint32_t other = 0;
      for (auto i = first[pick]; i < first[pick + 1]; ++i) {
        const auto u = around[i];
        if (u == t) continue;
        const auto& w = part.tets[u];
        const auto has = [&](GlobalId x) { return w[0] == x || w[1] == x || w[2] == x || w[3] == x; };
        if (has(a) && has(b) && has(d)) ++found, other = u;
      }
      if (found > 1) too_many(face_key(a, b, d), std::size_t(found) + 1);
      if (found == 0) {
        nb.open.push_back({std::uint32_t(t), std::int32_t(f)});
        continue;
      }
      nb.across[t][std::size_t(f)] = std::int32_t(other);
      const auto& w = part.tets[other];
      for (int e = 0; e < 4; ++e)  // the face of `other` without its vertex off the face
        if (w[std::size_t(e)] != a && w[std::size_t(e)] != b && w[std::size_t(e)] != d)
          nb.across[other][std::size_t(e)] = std::int32_t(t);
    }
  }
  return nb;
}

TetNeighbours neighbours(const Comm& comm, const Part& part, const VertexIndex& index) {
  const auto n = std::size_t(comm.size());
  TetNeighbours nb;
  nb.first = comm.exclusive_scan(std::int64_t(part.tets.size()));
  std::vector<std::vector<OpenFace>> out(n);
  comm.step([&] {
    auto local = local_neighbours(part, index);
    nb.local = std::move(local.across);
    for (const auto& [t, f] : local.open) {
      const auto& g = part.tets[t];
      const auto& c = kTetFaces[f];
      const auto key = face_key(g[std::size_t(c[0])], g[std::size_t(c[1])], g[std::size_t(c[2])]);
      out[std::size_t(owner_of(key, comm.size()))].push_back(
          {key, nb.first + GlobalId(t), std::int32_t(f), std::int32_t(comm.rank())});
    }
  });
  auto open = comm.exchange(out);
  out = {};
  // Pair them: each side hears of the other.
  std::vector<std::vector<Paired>> replies(n);
  comm.step([&] {
    std::sort(open.begin(), open.end(),
              [](const OpenFace& x, const OpenFace& y) { return x.key != y.key ? x.key < y.key : x.tet < y.tet; });
    for (std::size_t i = 0; i < open.size();) {
      std::size_t j = i + 1;
      while (j < open.size() && open[j].key == open[i].key) ++j;
      if (j - i > 2) too_many(open[i].key, j - i);
      if (j - i == 2) {
        const auto &x = open[i], &y = open[i + 1];
        replies[std::size_t(x.rank)].push_back({x.tet, y.tet, x.face, y.rank});
        replies[std::size_t(y.rank)].push_back({y.tet, x.tet, y.face, x.rank});
      }
      i = j;
    }
  });
  open = {};
  const auto paired = comm.exchange(replies);
  replies = {};
  nb.remote.reserve(paired.size());
  for (const auto& p : paired) nb.remote.push_back({std::uint32_t(p.tet - nb.first), p.face, p.other, p.rank});
  std::sort(nb.remote.begin(), nb.remote.end(),
            [](const RemoteFace& x, const RemoteFace& y) { return x.tet != y.tet ? x.tet < y.tet : x.face < y.face; });
  return nb;
}

std::vector<std::int32_t> values_across(const Comm& comm, const TetNeighbours& nb,
                                        const std::vector<std::int32_t>& per_tet) {
  std::vector<std::vector<ValueAcross>> out(std::size_t(comm.size()));
  for (const auto& r : nb.remote)
    out[std::size_t(r.rank)].push_back({r.other, nb.first + GlobalId(r.tet), per_tet[r.tet], 0});
  const auto got = comm.exchange(out);
  std::vector<std::int32_t> across(nb.remote.size(), 0);
  comm.step([&] {
    for (const auto& d : got) {
      const auto t = std::uint32_t(d.to - nb.first);
      auto [i, last] = remote_faces(nb, t);
      while (i < last && nb.remote[i].other != d.from) ++i;
      if (i == last) throw std::runtime_error("a face between ranks is known on one side");
      across[i] = d.value;
    }
  });
  return across;
}

}  // namespace metrica::distributed
