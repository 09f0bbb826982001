#include <metrica/distributed/neighbours.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <algorithm>

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

TetsAround::TetsAround(const Part& part) : first(part.vertex_ids.size() + 1, 0) {
  for (const auto& t : part.tets)
    for (auto v : t) ++first[v + 1];
  for (std::size_t v = 0; v + 1 < first.size(); ++v) first[v + 1] += first[v];
  around.resize(first.back());
  auto fill = first;
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (auto v : part.tets[t]) around[fill[v]++] = std::uint32_t(t);
}

LocalNeighbours local_neighbours(const Part& part) {
  LocalNeighbours nb;
  const std::size_t nt = part.tets.size(), nv = part.vertex_ids.size();
  // Each face is paired at its lowest vertex (local numbers), among the
  // tets listed there: a tet is listed under its two lowest vertices, the
  // lowest of each of its faces (8 bytes a tet). A face then costs a sort
  // of a few dozen sides, not a scan of the tets around one of its
  // vertices.
  const auto local_of = [&](std::size_t t) -> const LocalTet& { return part.tets[t]; };
  std::vector<std::uint32_t> first(nv + 1, 0);
  const auto lowest_two = [](const std::array<std::uint32_t, 4>& l) {
    std::uint32_t a = std::min(l[0], l[1]), b = std::max(l[0], l[1]);
    for (int c = 2; c < 4; ++c) {
      const auto x = l[std::size_t(c)];
      if (x < a)
        b = a, a = x;
      else if (x < b)
        b = x;
    }
    return std::pair{a, b};
  };
  nb.across.assign(nt, {-1, -1, -1, -1});
  for (std::size_t t = 0; t < nt; ++t) {
    const auto [a, b] = lowest_two(local_of(t));
    ++first[a + 1];
    ++first[b + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> listed(first.back());
  {
    auto fill = first;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto [a, b] = lowest_two(local_of(t));
      listed[fill[a]++] = std::uint32_t(t);
      listed[fill[b]++] = std::uint32_t(t);
    }
  }
  struct Side {
    std::uint32_t b, c, tet;
    std::int32_t face;
  };
  std::vector<Side> sides;
  for (std::uint32_t v = 0; v < nv; ++v) {
    sides.clear();
    for (auto i = first[v]; i < first[v + 1]; ++i) {
      const auto t = listed[i];
      const auto l = local_of(t);
      for (int f = 0; f < 4; ++f) {
        const auto& c = kTetFaces[f];
        std::uint32_t x = l[std::size_t(c[0])], y = l[std::size_t(c[1])], z = l[std::size_t(c[2])];
        if (x != v && y != v && z != v) continue;
        // The two vertices other than v, in order; v must be the lowest.
        std::uint32_t p = x == v ? y : x, q = x == v || y == v ? z : y;
        if (p > q) std::swap(p, q);
        if (p < v) continue;
        sides.push_back({p, q, t, std::int32_t(f)});
      }
    }
    std::sort(sides.begin(), sides.end(), [](const Side& m, const Side& n) {
      return m.b != n.b ? m.b < n.b : m.c != n.c ? m.c < n.c : m.tet != n.tet ? m.tet < n.tet : m.face < n.face;
    });
    for (std::size_t k = 0; k < sides.size();) {
      std::size_t e = k + 1;
      while (e < sides.size() && sides[e].b == sides[k].b && sides[e].c == sides[k].c) ++e;
      if (e - k > 2) {
        const auto& g = part.vertex_ids;
        too_many(face_key(g[v], g[sides[k].b], g[sides[k].c]), e - k);
      }
      if (e - k == 2) {
        nb.across[sides[k].tet][std::size_t(sides[k].face)] = std::int32_t(sides[k + 1].tet);
        nb.across[sides[k + 1].tet][std::size_t(sides[k + 1].face)] = std::int32_t(sides[k].tet);
      }
      k = e;
    }
  }
  for (std::size_t t = 0; t < nt; ++t)
    for (int f = 0; f < 4; ++f)
      if (nb.across[t][std::size_t(f)] < 0) nb.open.push_back({std::uint32_t(t), std::int32_t(f)});
  return nb;
}

TetNeighbours neighbours(const Comm& comm, const Part& part) {
  const auto n = std::size_t(comm.size());
  TetNeighbours nb;
  nb.first = comm.exclusive_scan(std::int64_t(part.tets.size()));
  std::vector<std::vector<OpenFace>> out(n);
  comm.step([&] {
    auto local = local_neighbours(part);
    nb.local = std::move(local.across);
    for (const auto& [t, f] : local.open) {
      const auto key = global_face(part, t, f);
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
