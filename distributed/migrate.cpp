#include <metrica/distributed/migrate.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <functional>
#include <numeric>

namespace metrica::distributed {

namespace {

struct TetRecord {
  std::array<GlobalId, 4> v;
  std::int32_t ref;
  std::int32_t focus;                  // -1: no focus (all tets adapted)
  std::array<std::int32_t, 4> across;  // per face, the rank across when it is another one; else -1
};
struct VertexRecord {
  GlobalId id;
  Coords p;
  Sym6 m;
};
// A face at its pairing rank: a tet's face (kind 0, value: the tet's new
// rank) or a triangle (kind 1, or 3 when its key turned it over; value:
// its surface id).
struct FaceRecord {
  FaceKey key;
  std::int32_t kind, value;
};
// Back to a rank: a triangle of its part (kind 1 or 3, value: surface id)
// or a face it shares (kind 2, value: the rank across).
using FaceReply = FaceRecord;
// A triangle with the tet it lies on.
struct TriangleRecord {
  std::array<GlobalId, 3> v;
  std::int32_t ref, pad = 0;
};

// The vertices, sent once to each rank, with the tets.
void pack_tets(const Part& part, const VertexIndex& index, const std::vector<int>& dest,
               const std::function<std::array<std::int32_t, 4>(std::size_t)>& across,
               std::vector<std::vector<TetRecord>>& tets_out, std::vector<std::vector<VertexRecord>>& verts_out) {
  const auto n = tets_out.size();
  std::vector<std::vector<std::uint32_t>> by_rank(n);
  for (std::size_t t = 0; t < part.tets.size(); ++t) by_rank[std::size_t(dest[t])].push_back(std::uint32_t(t));
  std::vector<int> sent_to(part.vertex_ids.size(), -1);
  for (std::size_t q = 0; q < n; ++q)
    for (auto t : by_rank[q]) {
      tets_out[q].push_back({part.tets[t], part.tet_refs[t], part.focus.empty() ? -1 : int(part.focus[t]), across(t)});
      for (GlobalId g : part.tets[t]) {
        const auto v = std::size_t(index.find(g));
        if (sent_to[v] == int(q)) continue;
        sent_to[v] = int(q);
        verts_out[q].push_back({g, coords(part.points[v]), part.metrics.empty() ? Sym6{} : part.metrics[v]});
      }
    }
}

// The received vertices (once each: several ranks may send the same), tets and focus.
void unpack_tets(const Comm& comm, const Part& part, const std::vector<VertexRecord>& verts_in,
                 const std::vector<TetRecord>& tets_in, Part& out) {
  std::vector<std::uint32_t> order(verts_in.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return verts_in[a].id < verts_in[b].id; });
  // Every rank takes part in the reduction (an empty part has no metrics
  // to say whether the others carry them).
  const bool metric = comm.max(std::int64_t(part.metrics.size())) > 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto& r = verts_in[order[i]];
    if (i > 0 && verts_in[order[i - 1]].id == r.id) continue;
    out.vertex_ids.push_back(r.id);
    out.points.push_back(point(r.p));
    if (metric) out.metrics.push_back(r.m);
  }
  for (const auto& t : tets_in) out.tets.push_back(t.v), out.tet_refs.push_back(t.ref);
  if (comm.max(std::int64_t(part.focus.empty() ? 0 : 1)) > 0)
    for (const auto& t : tets_in) out.focus.push_back(t.focus > 0 ? 1 : 0);
}

// A part as read (triangles anywhere, faces between ranks unknown): every
// face meets its tets and triangles at the rank its key hashes to.
Part migrate_by_rendezvous(const Comm& comm, const Part& part, const VertexIndex& index, const std::vector<int>& dest) {
  const auto n = std::size_t(comm.size());
  std::vector<std::vector<TetRecord>> tets_out(n);
  std::vector<std::vector<VertexRecord>> verts_out(n);
  pack_tets(
      part, index, dest,
      [](std::size_t) {
        return std::array<std::int32_t, 4>{-1, -1, -1, -1};
      },
      tets_out, verts_out);
  std::vector<std::vector<FaceRecord>> faces_out(n);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (const auto& f : kTetFaces) {
      const auto& v = part.tets[t];
      const auto key = face_key(v[f[0]], v[f[1]], v[f[2]]);
      faces_out[std::size_t(owner_of(key, comm.size()))].push_back({key, 0, dest[t]});
    }
  for (std::size_t i = 0; i < part.triangles.size(); ++i) {
    const auto key = face_key(part.triangles[i]);
    faces_out[std::size_t(owner_of(key, comm.size()))].push_back(
        {key, turned_over(part.triangles[i]) ? 3 : 1, part.triangle_refs[i]});
  }

  auto tets_in = comm.exchange(tets_out);
  tets_out = {};
  auto verts_in = comm.exchange(verts_out);
  verts_out = {};
  auto faces_in = comm.exchange(faces_out);
  faces_out = {};

  std::vector<std::vector<FaceReply>> replies(n);
  comm.step([&] {
    std::sort(faces_in.begin(), faces_in.end(), [](const FaceRecord& a, const FaceRecord& b) {
      return a.key != b.key ? a.key < b.key : a.kind != b.kind ? a.kind < b.kind : a.value < b.value;
    });
    for (std::size_t i = 0; i < faces_in.size();) {
      std::size_t j = i;
      int ranks[2] = {-1, -1}, tets = 0;
      while (j < faces_in.size() && faces_in[j].key == faces_in[i].key && faces_in[j].kind == 0) {
        if (tets < 2) ranks[tets] = faces_in[j].value;
        ++tets, ++j;
      }
      const bool triangle = j < faces_in.size() && faces_in[j].key == faces_in[i].key;
      const auto& k = faces_in[i].key;
      if (tets > 2)
        throw InputError(
            fmt::format("the face ({} {} {}) has {} tets (at most 2)", k[0] + 1, k[1] + 1, k[2] + 1, tets));
      if (triangle && tets == 0)
        throw InputError(fmt::format("the triangle ({} {} {}) is not a face of any tet", k[0] + 1, k[1] + 1, k[2] + 1));
      if (triangle) {
        // A triangle listed twice keeps its first (smallest) id.
        const FaceReply r{k, faces_in[j].kind, faces_in[j].value};
        replies[std::size_t(ranks[0])].push_back(r);
        if (tets == 2 && ranks[1] != ranks[0]) replies[std::size_t(ranks[1])].push_back(r);
      }
      if (tets == 2 && ranks[0] != ranks[1]) {
        replies[std::size_t(ranks[0])].push_back({k, 2, ranks[1]});
        replies[std::size_t(ranks[1])].push_back({k, 2, ranks[0]});
      }
      while (j < faces_in.size() && faces_in[j].key == k) ++j;
      i = j;
    }
  });
  faces_in = {};
  auto got = comm.exchange(replies);
  replies = {};

  Part out;
  unpack_tets(comm, part, verts_in, tets_in, out);
  std::sort(got.begin(), got.end(),
            [](const FaceReply& a, const FaceReply& b) { return a.key != b.key ? a.key < b.key : a.kind < b.kind; });
  for (const auto& r : got) {
    if (r.kind == 1 || r.kind == 3)
      out.triangles.push_back(oriented(r.key, r.kind == 3)), out.triangle_refs.push_back(r.value);
    if (r.kind == 2) out.shared_faces.push_back(r.key), out.shared_with.push_back(r.value);
  }
  out.faces_known = true;
  return out;
}

}  // namespace

Part migrate(const Comm& comm, const Part& part, const TetNeighbours& nb, const std::vector<int>& dest) {
  const VertexIndex index(part.vertex_ids);
  if (comm.max(std::int64_t(part.faces_known ? 0 : 1)) > 0) return migrate_by_rendezvous(comm, part, index, dest);
  const auto n = std::size_t(comm.size());
  // The new ranks of the tets across the faces between ranks.
  const auto remote_dest = values_across(comm, nb, std::vector<std::int32_t>(dest.begin(), dest.end()));
  std::vector<std::vector<TetRecord>> tets_out(n);
  std::vector<std::vector<VertexRecord>> verts_out(n);
  std::vector<std::array<std::int32_t, 4>> across(part.tets.size(), {-1, -1, -1, -1});
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      const auto u = nb.local[t][std::size_t(f)];
      if (u >= 0 && dest[std::size_t(u)] != dest[t]) across[t][std::size_t(f)] = dest[std::size_t(u)];
    }
  for (std::size_t i = 0; i < nb.remote.size(); ++i) {
    const auto& r = nb.remote[i];
    if (remote_dest[i] != dest[r.tet]) across[r.tet][std::size_t(r.face)] = remote_dest[i];
  }
  pack_tets(
      part, index, dest, [&](std::size_t t) { return across[t]; }, tets_out, verts_out);
  across = {};
  // Each triangle with the tets whose face it is (both of an internal
  // surface's; the receiver keeps one of each).
  std::vector<std::vector<TriangleRecord>> tris_out(n);
  comm.step([&] {
    std::vector<std::pair<FaceKey, std::uint32_t>> keys;
    for (std::size_t i = 0; i < part.triangles.size(); ++i) keys.emplace_back(face_key(part.triangles[i]), i);
    std::sort(keys.begin(), keys.end());
    std::vector<bool> placed(keys.size(), false);
    for (std::size_t t = 0; t < part.tets.size() && !keys.empty(); ++t) {
      const auto& v = part.tets[t];
      for (const auto& f : kTetFaces) {
        const auto key = face_key(v[std::size_t(f[0])], v[std::size_t(f[1])], v[std::size_t(f[2])]);
        auto it = std::lower_bound(keys.begin(), keys.end(), std::pair<FaceKey, std::uint32_t>{key, 0});
        for (; it != keys.end() && it->first == key; ++it) {
          const auto i = it->second;
          placed[std::size_t(it - keys.begin())] = true;
          tris_out[std::size_t(dest[t])].push_back({part.triangles[i], part.triangle_refs[i]});
        }
      }
    }
    if (std::find(placed.begin(), placed.end(), false) != placed.end())
      throw std::runtime_error("migrate: a triangle of the part is no face of its tets");
  });

  auto tets_in = comm.exchange(tets_out);
  tets_out = {};
  auto verts_in = comm.exchange(verts_out);
  verts_out = {};
  auto tris_in = comm.exchange(tris_out);
  tris_out = {};

  Part out;
  unpack_tets(comm, part, verts_in, tets_in, out);
  verts_in = {};
  std::vector<std::pair<FaceKey, std::int32_t>> shared;
  for (const auto& t : tets_in)
    for (int f = 0; f < 4; ++f)
      if (t.across[std::size_t(f)] >= 0) {
        const auto& c = kTetFaces[f];
        shared.emplace_back(face_key(t.v[std::size_t(c[0])], t.v[std::size_t(c[1])], t.v[std::size_t(c[2])]),
                            t.across[std::size_t(f)]);
      }
  tets_in = {};
  std::sort(shared.begin(), shared.end());
  for (const auto& [k, r] : shared) out.shared_faces.push_back(k), out.shared_with.push_back(r);
  // One of each triangle (the smallest id when a face was listed twice).
  std::sort(tris_in.begin(), tris_in.end(), [](const TriangleRecord& a, const TriangleRecord& b) {
    const auto ka = face_key(a.v), kb = face_key(b.v);
    return ka != kb ? ka < kb : a.ref < b.ref;
  });
  for (std::size_t i = 0; i < tris_in.size(); ++i) {
    if (i > 0 && face_key(tris_in[i].v) == face_key(tris_in[i - 1].v)) continue;
    out.triangles.push_back(tris_in[i].v), out.triangle_refs.push_back(tris_in[i].ref);
  }
  out.faces_known = true;
  return out;
}

}  // namespace metrica::distributed
