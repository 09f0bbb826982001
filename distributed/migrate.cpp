#include <metrica/distributed/migrate.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

namespace metrica::distributed {

namespace {

// A tet whose vertices are numbered in the list of vertices its sender
// sent the same rank (24 bytes, not 40 with global ids).
struct TetRecord {
  std::array<std::uint32_t, 4> v;
  std::int32_t ref;
  std::int32_t focus;  // -1: no focus (all tets adapted)
};
// A face of a tet sent, shared at its new rank with the rank across.
struct SharedRecord {
  FaceKey key;
  std::int32_t rank, pad = 0;
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

// Tets with their vertices on their way: per destination rank, then as
// received (with how many came from each rank). The vertices' CAD
// parameters, when the mesh has a model, travel beside them in the same
// order.
struct Outgoing {
  std::vector<std::vector<TetRecord>> tets;
  std::vector<std::vector<VertexRecord>> verts;
  std::vector<std::vector<GeoParam>> geo;
  explicit Outgoing(std::size_t ranks) : tets(ranks), verts(ranks), geo(ranks) {}
};
struct Arrived {
  std::vector<TetRecord> tets;
  std::vector<VertexRecord> verts;
  std::vector<GeoParam> geo;
  std::vector<std::int64_t> tets_from, verts_from;
};
// `geo`: whether any rank's part has CAD parameters (the same on all).
Arrived deliver(const Comm& comm, Outgoing& out, bool geo) {
  Arrived in;
  in.tets = comm.exchange(out.tets, &in.tets_from);
  out.tets = {};
  in.verts = comm.exchange(out.verts, &in.verts_from);
  out.verts = {};
  if (geo) in.geo = comm.exchange(out.geo);
  out.geo = {};
  return in;
}

// The tets leaving for other ranks (all but those for rank `stay`), each
// rank's vertices sent once with them.
void pack_tets(const Part& part, const std::vector<int>& dest, int stay, Outgoing& out) {
  auto& tets_out = out.tets;
  auto& verts_out = out.verts;
  const auto n = tets_out.size();
  // Every list sized once (grown by doubling, they held up to twice the
  // records beside the part).
  std::vector<std::size_t> leaving(n, 0);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    if (dest[t] != stay) ++leaving[std::size_t(dest[t])];
  std::vector<std::vector<std::uint32_t>> by_rank(n);
  for (std::size_t q = 0; q < n; ++q) by_rank[q].reserve(leaving[q]);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    if (dest[t] != stay) by_rank[std::size_t(dest[t])].push_back(std::uint32_t(t));
  std::vector<int> sent_to(part.vertex_ids.size(), -1);
  for (std::size_t q = 0; q < n; ++q) {
    std::size_t verts = 0;
    for (auto t : by_rank[q])
      for (auto v : part.tets[t])
        if (sent_to[v] != int(q)) sent_to[v] = int(q), ++verts;
    tets_out[q].reserve(by_rank[q].size());
    verts_out[q].reserve(verts);
    if (!part.geo.empty()) out.geo[q].reserve(verts);
  }
  std::fill(sent_to.begin(), sent_to.end(), -1);
  std::vector<std::uint32_t> slot(part.vertex_ids.size());  // in verts_out[q], once sent to q
  for (std::size_t q = 0; q < n; ++q)
    for (auto t : by_rank[q]) {
      TetRecord r{{}, part.tet_refs[t], part.focus.empty() ? -1 : int(part.focus[t])};
      for (int c = 0; c < 4; ++c) {
        const auto v = part.tets[t][std::size_t(c)];
        if (sent_to[v] != int(q)) {
          sent_to[v] = int(q);
          slot[v] = std::uint32_t(verts_out[q].size());
          verts_out[q].push_back(
              {part.vertex_ids[v], coords(part.points[v]), part.metrics.empty() ? Sym6{} : part.metrics[v]});
          if (!part.geo.empty()) out.geo[q].push_back(part.geo[v]);
        }
        r.v[std::size_t(c)] = slot[v];
      }
      tets_out[q].push_back(r);
    }
}

// Appends what arrived to `out`: each vertex `out` does not hold yet,
// once (several ranks may send the same; the first sender's copy), then
// the tets with their refs and focus, a record's vertices named in the
// list the same rank sent. The arrays grow once, to their size (a
// doubling would hold both copies); `in` is emptied.
void append_arrived(Arrived& in, bool metric, bool focus, bool geo, Part& out) {
  const auto& verts = in.verts;
  std::vector<std::uint32_t> local(verts.size());  // of each vertex received
  {
    const VertexIndex held(out.vertex_ids);
    std::vector<std::uint32_t> order(verts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::uint32_t(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return verts[a].id < verts[b].id; });
    out.vertex_ids.reserve(out.vertex_ids.size() + verts.size());
    out.points.reserve(out.points.size() + verts.size());
    if (metric) out.metrics.reserve(out.metrics.size() + verts.size());
    if (geo) out.geo.reserve(out.geo.size() + verts.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& r = verts[order[k]];
      if (k > 0 && verts[order[k - 1]].id == r.id) {
        local[order[k]] = local[order[k - 1]];
        continue;
      }
      if (const auto h = held.find(r.id); h >= 0) {
        local[order[k]] = std::uint32_t(h);
        continue;
      }
      local[order[k]] = std::uint32_t(out.vertex_ids.size());
      out.vertex_ids.push_back(r.id);
      out.points.push_back(point(r.p));
      if (metric) out.metrics.push_back(r.m);
      if (geo) out.geo.push_back(in.geo[order[k]]);
    }
  }
  in.verts = {};
  in.geo = {};
  out.tets.reserve(out.tets.size() + in.tets.size());
  out.tet_refs.reserve(out.tet_refs.size() + in.tets.size());
  if (focus) out.focus.reserve(out.focus.size() + in.tets.size());
  std::size_t t = 0, base = 0;
  for (std::size_t s = 0; s < in.tets_from.size(); ++s) {
    for (std::int64_t i = 0; i < in.tets_from[s]; ++i, ++t) {
      const auto& r = in.tets[t];
      out.tets.push_back({local[base + r.v[0]], local[base + r.v[1]], local[base + r.v[2]], local[base + r.v[3]]});
      out.tet_refs.push_back(r.ref);
      if (focus) out.focus.push_back(r.focus > 0 ? 1 : 0);
    }
    base += std::size_t(in.verts_from[s]);
  }
  in.tets = {};
}

// A part as read (triangles anywhere, faces between ranks unknown): every
// face meets its tets and triangles at the rank its key hashes to.
Part migrate_by_rendezvous(const Comm& comm, const Part& part, const std::vector<int>& dest) {
  const auto n = std::size_t(comm.size());
  Outgoing travelling(n);
  pack_tets(part, dest, -1, travelling);
  std::vector<std::vector<FaceRecord>> faces_out(n);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      const auto key = global_face(part, t, f);
      faces_out[std::size_t(owner_of(key, comm.size()))].push_back({key, 0, dest[t]});
    }
  for (std::size_t i = 0; i < part.triangles.size(); ++i) {
    const auto key = face_key(part.triangles[i]);
    faces_out[std::size_t(owner_of(key, comm.size()))].push_back(
        {key, turned_over(part.triangles[i]) ? 3 : 1, part.triangle_refs[i]});
  }

  const bool geo = comm.max(std::int64_t(part.geo.size())) > 0;
  Arrived in = deliver(comm, travelling, geo);
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

  // Every rank takes part in the reductions (an empty part has no metrics
  // to say whether the others carry them).
  const bool metric = comm.max(std::int64_t(part.metrics.size())) > 0;
  const bool focus = comm.max(std::int64_t(part.focus.empty() ? 0 : 1)) > 0;
  Part out;
  append_arrived(in, metric, focus, geo, out);
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

Part migrate(const Comm& comm, Part part, TetNeighbours nb, const std::vector<int>& dest) {
  const int me = comm.rank();
  const auto n = std::size_t(comm.size());
  Outgoing travelling(n);
  std::vector<std::vector<TriangleRecord>> tris_out(n);
  std::vector<std::vector<SharedRecord>> shared_out(n);
  std::vector<std::pair<FaceKey, std::int32_t>> shared;  // the faces between ranks of the tets that stay
  std::vector<bool> triangle_stays(part.triangles.size(), false);
  {
    if (comm.max(std::int64_t(part.faces_known ? 0 : 1)) > 0) return migrate_by_rendezvous(comm, part, dest);
    // The new ranks of the tets across the faces between ranks.
    const auto remote_dest = values_across(comm, nb, dest);
    // Per face of tet t, the new rank across it when that is not t's.
    const auto across = [&](std::size_t t) {
      std::array<std::int32_t, 4> a{-1, -1, -1, -1};
      for (int f = 0; f < 4; ++f) {
        const auto u = nb.local[t][std::size_t(f)];
        if (u >= 0 && dest[std::size_t(u)] != dest[t]) a[std::size_t(f)] = dest[std::size_t(u)];
      }
      const auto [lo, hi] = remote_faces(nb, std::uint32_t(t));
      for (auto i = lo; i < hi; ++i) {
        const auto d = remote_dest[i];
        if (d != dest[t]) a[std::size_t(nb.remote[i].face)] = d;
      }
      return a;
    };
    pack_tets(part, dest, me, travelling);
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      const auto a = across(t);
      for (int f = 0; f < 4; ++f)
        if (a[std::size_t(f)] >= 0) {
          const auto key = global_face(part, t, f);
          if (dest[t] == me)
            shared.emplace_back(key, a[std::size_t(f)]);
          else
            shared_out[std::size_t(dest[t])].push_back({key, a[std::size_t(f)]});
        }
    }
  }
  nb = TetNeighbours{};  // all it told is in `shared` and `shared_out` now
  // Each triangle with the tets whose face it is (both of an internal
  // surface's; the receiver keeps one of each).
  comm.step([&] {
    std::vector<std::pair<FaceKey, std::uint32_t>> keys;
    for (std::size_t i = 0; i < part.triangles.size(); ++i) keys.emplace_back(face_key(part.triangles[i]), i);
    std::sort(keys.begin(), keys.end());
    std::vector<bool> placed(keys.size(), false);
    for (std::size_t t = 0; t < part.tets.size() && !keys.empty(); ++t) {
      for (int f = 0; f < 4; ++f) {
        const auto key = global_face(part, t, f);
        auto it = std::lower_bound(keys.begin(), keys.end(), std::pair<FaceKey, std::uint32_t>{key, 0});
        for (; it != keys.end() && it->first == key; ++it) {
          const auto i = it->second;
          placed[std::size_t(it - keys.begin())] = true;
          if (dest[t] == me)
            triangle_stays[i] = true;
          else
            tris_out[std::size_t(dest[t])].push_back({part.triangles[i], part.triangle_refs[i]});
        }
      }
    }
    if (std::find(placed.begin(), placed.end(), false) != placed.end())
      throw std::runtime_error("migrate: a triangle of the part is no face of its tets");
  });

  const bool metric = comm.max(std::int64_t(part.metrics.size())) > 0;
  const bool focus = comm.max(std::int64_t(part.focus.empty() ? 0 : 1)) > 0;
  const bool geo = comm.max(std::int64_t(part.geo.size())) > 0;
  // What stays, compacted in place: the tets, the vertices they use, the triangles.
  {
    std::vector<bool> stays(part.tets.size());
    for (std::size_t t = 0; t < stays.size(); ++t) stays[t] = dest[t] == me;
    keep_tets(part, stays);
    if (focus) part.focus.resize(part.tets.size(), 0);
    std::vector<bool> used(part.vertex_ids.size(), false);
    for (const auto& t : part.tets)
      for (auto v : t) used[v] = true;
    keep_vertices(part, used);
    keep_triangles(part, triangle_stays);
  }

  Arrived in = deliver(comm, travelling, geo);
  auto tris_in = comm.exchange(tris_out);
  tris_out = {};
  for (const auto& r : comm.exchange(shared_out)) shared.emplace_back(r.key, r.rank);
  shared_out = {};

  // What arrives: the tets, new vertices once each (this part may hold
  // some already), their shared faces.
  append_arrived(in, metric, focus, geo, part);
  std::sort(shared.begin(), shared.end());
  part.shared_faces.clear();
  part.shared_with.clear();
  for (const auto& [k, r] : shared) part.shared_faces.push_back(k), part.shared_with.push_back(r);
  // One of each triangle (the smallest id when a face was listed twice).
  for (std::size_t i = 0; i < part.triangles.size(); ++i) tris_in.push_back({part.triangles[i], part.triangle_refs[i]});
  std::sort(tris_in.begin(), tris_in.end(), [](const TriangleRecord& a, const TriangleRecord& b) {
    const auto ka = face_key(a.v), kb = face_key(b.v);
    return ka != kb ? ka < kb : a.ref < b.ref;
  });
  part.triangles.clear();
  part.triangle_refs.clear();
  for (std::size_t i = 0; i < tris_in.size(); ++i) {
    if (i > 0 && face_key(tris_in[i].v) == face_key(tris_in[i - 1].v)) continue;
    part.triangles.push_back(tris_in[i].v), part.triangle_refs.push_back(tris_in[i].ref);
  }
  part.faces_known = true;
  return part;
}

}  // namespace metrica::distributed
