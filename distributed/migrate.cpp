#include <metrica/distributed/migrate.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <numeric>

namespace metrica::distributed {

namespace {

struct TetRecord {
  std::array<GlobalId, 4> v;
  std::int32_t ref;
  std::int32_t focus;  // -1: no focus (all tets adapted)
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

}  // namespace

Part migrate(const Comm& comm, const Part& part, const std::vector<int>& dest) {
  const auto n = std::size_t(comm.size());
  const VertexIndex index(part.vertex_ids);
  std::vector<std::vector<TetRecord>> tets_out(n);
  std::vector<std::vector<VertexRecord>> verts_out(n);
  {
    std::vector<std::vector<std::uint32_t>> by_rank(n);
    for (std::size_t t = 0; t < part.tets.size(); ++t) by_rank[std::size_t(dest[t])].push_back(std::uint32_t(t));
    std::vector<int> sent_to(part.vertex_ids.size(), -1);
    for (std::size_t q = 0; q < n; ++q)
      for (auto t : by_rank[q]) {
        tets_out[q].push_back({part.tets[t], part.tet_refs[t], part.focus.empty() ? -1 : int(part.focus[t])});
        for (GlobalId g : part.tets[t]) {
          const auto v = std::size_t(index.find(g));
          if (sent_to[v] == int(q)) continue;
          sent_to[v] = int(q);
          verts_out[q].push_back({g, coords(part.points[v]), part.metrics.empty() ? Sym6{} : part.metrics[v]});
        }
      }
  }
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
  // Vertices by global id, once each (several ranks may send the same).
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
  std::sort(got.begin(), got.end(),
            [](const FaceReply& a, const FaceReply& b) { return a.key != b.key ? a.key < b.key : a.kind < b.kind; });
  for (const auto& r : got) {
    if (r.kind == 1 || r.kind == 3)
      out.triangles.push_back(oriented(r.key, r.kind == 3)), out.triangle_refs.push_back(r.value);
    if (r.kind == 2) out.shared_faces.push_back(r.key), out.shared_with.push_back(r.value);
  }
  return out;
}

}  // namespace metrica::distributed
