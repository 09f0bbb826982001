// Cavities read from connectivity only (the "find" step of docs/architecture.md):
// the ball of a vertex (its incident tets) and the shell of an edge (the
// tets around it, in rotation order). No allocation: small vectors sized
// for the usual cases spill to the heap only for unusual valences.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/small_vector.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace metrica {

// The operators append to these small vectors with emplace_back: Boost
// (1.74) force-inlines its fast path, while push_back is a call on every
// append (5% of a one-thread adaptation went to those calls).
using TetList = boost::container::small_vector<TetId, 64>;
using VertexList = boost::container::small_vector<VertexId, 64>;

// A read-only view of a small vector (boost's iterators are not C++20
// contiguous iterators, so std::span does not convert on its own).
template <class T, std::size_t N>
std::span<const T> view(const boost::container::small_vector<T, N>& v) {
  return {v.data(), v.size()};
}

// A set of ids for the cavity walks: an open-addressing table on the
// stack (no allocation, O(1) membership), with a linear search of the
// caller's list kept for the rare cavities too large for it. Linear
// searches of the lists cost 10% of an adaptation.
class SmallIdSet {
 public:
  SmallIdSet() { slots_.fill(kNoId); }
  // True when id was not in the set (and adds it). `list` holds every id
  // added so far (the caller's list, searched once the table is half full).
  template <class List>
  bool insert(std::uint32_t id, const List& list) {
    if (count_ >= kMaxLoad) return std::find(list.begin(), list.end(), id) == list.end();
    std::size_t h = (id * 2654435761u) >> 24;
    while (slots_[h] != kNoId) {
      if (slots_[h] == id) return false;
      h = (h + 1) & (kSlots - 1);
    }
    slots_[h] = id;
    ++count_;
    return true;
  }

 private:
  static constexpr std::size_t kSlots = 256, kMaxLoad = 128;
  std::array<std::uint32_t, kSlots> slots_;
  std::size_t count_ = 0;
};

// The walk over the tets containing v, across faces through v, from v's
// hint, listing them in `ball`; it stops at the first tet for which
// stop(t) holds and returns it (kNoId when the walk ends).
template <class Stop>
TetId walk_vertex_ball(const Mesh& mesh, VertexId v, TetList& ball, Stop&& stop) {
  ball.clear();
  const TetId start = mesh.vert2tet(v);
  if (start == kNoId || !mesh.tet_alive(start)) return kNoId;
  SmallIdSet seen;
  seen.insert(start, ball);
  ball.emplace_back(start);
  for (std::size_t k = 0; k < ball.size(); ++k) {
    const TetId t = ball[k];
    if (stop(t)) return t;
    const int iv = local_index(mesh.tet(t), v);
    for (int f = 0; f < 4; ++f) {
      if (f == iv) continue;  // the face opposite v does not contain it
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid() && seen.insert(n.tet(), ball)) {
        // The walk is a chain of dependent loads (a tet's vertices, then
        // its neighbours), most of them cache misses on a large mesh: ask
        // for the new tet's lines now, a few tets before it is read.
        mesh.prefetch_tet(n.tet());
        ball.emplace_back(n.tet());
      }
    }
  }
  return kNoId;
}

// The tets containing v.
inline void vertex_ball(const Mesh& mesh, VertexId v, TetList& ball) {
  walk_vertex_ball(mesh, v, ball, [](TetId) { return false; });
}

// A live tet holding edge ab (kNoId when none): a's walk stopped at the
// first such tet (a shell's start without the whole ball). `walk` is
// scratch.
inline TetId tet_with_edge(const Mesh& mesh, VertexId a, VertexId b, TetList& walk) {
  return walk_vertex_ball(mesh, a, walk, [&](TetId t) { return local_index(mesh.tet(t), b) >= 0; });
}

// A live tet holding face pqr (kNoId when none): p's walk stopped at the
// first tet that also holds q and r. `walk` is scratch.
inline TetId tet_with_face(const Mesh& mesh, VertexId p, VertexId q, VertexId r, TetList& walk) {
  return walk_vertex_ball(mesh, p, walk, [&](TetId t) {
    const TetVertices v = mesh.tet(t);
    return local_index(v, q) >= 0 && local_index(v, r) >= 0;
  });
}

// Appends to `list` the vertices of `tets` it does not hold yet (the
// vertex set of a cavity, to lock).
template <class Tets>
void append_vertices(const Mesh& mesh, const Tets& tets, VertexList& list) {
  SmallIdSet seen;
  for (VertexId v : list) seen.insert(v, list);  // (all already in the list)
  for (TetId t : tets)
    for (VertexId v : mesh.tet(t))
      if (seen.insert(v, list)) list.emplace_back(v);
}

// Appends to `list` the ids of `ids` it does not hold yet.
inline void append_new(const VertexList& ids, VertexList& list) {
  SmallIdSet seen;
  for (VertexId v : list) seen.insert(v, list);  // (all already in the list)
  for (VertexId v : ids)
    if (seen.insert(v, list)) list.emplace_back(v);
}

// Marks (1) the vertices of the tets written since epoch `since`: the
// vertices whose ball changed. On C's threads, each over a slice of the
// tets (relaxed atomic stores: parts may mark one vertex together).
template <class C = Serial>
std::vector<std::uint8_t> changed_vertices(const Mesh& mesh, Mesh::Epoch since) {
  std::vector<std::uint8_t> changed(mesh.vertex_capacity(), 0);
  const std::size_t n = mesh.tet_capacity();
  const std::size_t parts = sweep_parts<C>(n);
  C::parallel_for(parts, [&](std::size_t p) {
    for (auto t = static_cast<TetId>(n * p / parts); t < n * (p + 1) / parts; ++t)
      if (mesh.tet_alive(t) && mesh.changed_since(t, since))
        for (VertexId v : mesh.tet(t)) std::atomic_ref<std::uint8_t>(changed[v]).store(1, std::memory_order_relaxed);
  });
  return changed;
}

// The vertices joined to v by an edge.
inline void vertex_neighbours(const Mesh& mesh, const TetList& ball, VertexId v, VertexList& out) {
  out.clear();
  SmallIdSet seen;
  for (TetId t : ball)
    for (VertexId w : mesh.tet(t))
      if (w != v && seen.insert(w, out)) out.emplace_back(w);
}

// The shell of edge ab: the tets containing both, in rotation order about
// the edge; `closed` is false when the edge is on the boundary (the shell
// then starts and ends at boundary faces). False when no tet holds ab.
// The two vertices of tet t other than a and b.
inline std::array<VertexId, 2> edge_opposite(const TetVertices& t, VertexId a, VertexId b) {
  std::array<VertexId, 2> o{kNoId, kNoId};
  int k = 0;
  for (VertexId w : t)
    if (w != a && w != b) o[k++] = w;
  return o;
}

struct Shell {
  TetList tets;
  bool closed = true;
};

// The shell of ab from `start`, a live tet that contains both.
inline void edge_shell_from(const Mesh& mesh, VertexId a, VertexId b, TetId start, Shell& shell);

inline bool edge_shell(const Mesh& mesh, VertexId a, VertexId b, const TetList& ball_of_a, Shell& shell) {
  shell.tets.clear();
  for (TetId t : ball_of_a)
    if (local_index(mesh.tet(t), b) >= 0) {
      edge_shell_from(mesh, a, b, t, shell);
      return true;
    }
  return false;
}

inline void edge_shell_from(const Mesh& mesh, VertexId a, VertexId b, TetId start, Shell& shell) {
  shell.tets.clear();
  // Turn one way: from t leave through the face opposite one of the two
  // other vertices; the next tet shares a, b and the remaining vertex.
  auto step = [&](TetId t, VertexId through_kept) -> TetId {
    const auto& v = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      const VertexId opposite = v[f];
      if (opposite == a || opposite == b || opposite == through_kept) continue;
      const FaceRef n = mesh.neighbour(t, f);
      return n.valid() ? n.tet() : kNoId;
    }
    return kNoId;
  };
  // The vertex kept in the face we cross: the one shared with the next tet.
  auto others = [&](TetId t) { return edge_opposite(mesh.tet(t), a, b); };
  shell.closed = true;
  shell.tets.emplace_back(start);
  VertexId kept = others(start)[0];
  TetId t = start;
  for (;;) {
    const TetId next = step(t, kept);
    if (next == kNoId) {
      shell.closed = false;
      break;
    }
    if (next == start) break;
    const auto o = others(next);
    kept = (o[0] == kept) ? o[1] : o[0];
    shell.tets.emplace_back(next);
    t = next;
  }
  if (!shell.closed) {
    // Walk the other way from start and prepend, so that the list runs
    // from one boundary face to the other.
    TetList back;
    kept = others(start)[1];
    t = start;
    for (;;) {
      const TetId next = step(t, kept);
      if (next == kNoId) break;
      const auto o = others(next);
      kept = (o[0] == kept) ? o[1] : o[0];
      back.emplace_back(next);
      t = next;
    }
    for (std::size_t k = 0; k < shell.tets.size(); ++k) back.emplace_back(shell.tets[k]);
    // back holds the reverse walk then the forward one; put the reverse
    // walk in order (the forward part already is).
    const std::size_t nback = back.size() - shell.tets.size();
    std::reverse(back.begin(), back.begin() + static_cast<std::ptrdiff_t>(nback));
    shell.tets.swap(back);
  }
}

// The shell of edge ab from a's walk stopped at the first tet holding b
// (the start the whole ball would give, at half a ball's cache misses);
// false when ab is no edge. `walk` is scratch.
inline bool find_edge_shell(const Mesh& mesh, VertexId a, VertexId b, TetList& walk, Shell& shell) {
  const TetId start = tet_with_edge(mesh, a, b, walk);
  if (start == kNoId) return false;
  edge_shell_from(mesh, a, b, start, shell);
  return true;
}

// Appends the ring of ab's shell to `list` in rotation order: tet k of
// the shell is (a, b, v_k, v_{k+1}), so after the first tet (v_0, then the
// vertex it shares with the second) each tet adds the ring vertex it does
// not share with the one before; closed shells have as many ring vertices
// as tets, open ones one more.
inline void append_ring(const Mesh& mesh, VertexId a, VertexId b, const Shell& shell, VertexList& list) {
  const std::size_t n = shell.tets.size();
  if (n == 0) return;
  auto others = [&](TetId t) { return edge_opposite(mesh.tet(t), a, b); };
  const auto o0 = others(shell.tets[0]);
  if (n == 1) {
    list.emplace_back(o0[0]);
    list.emplace_back(o0[1]);
    return;
  }
  const auto o1 = others(shell.tets[1]);
  const VertexId shared = (o0[0] == o1[0] || o0[0] == o1[1]) ? o0[0] : o0[1];
  list.emplace_back(shared == o0[0] ? o0[1] : o0[0]);
  list.emplace_back(shared);
  for (std::size_t k = 1; k < n; ++k) {
    const auto o = others(shell.tets[k]);
    const VertexId next = (o[0] == list.back()) ? o[1] : o[0];
    if (k + 1 < n || !shell.closed) list.emplace_back(next);
  }
}

// Appends a, b and the ring of ab's shell to `list`: each vertex of the
// shell once, without the set append_vertices needs.
inline void append_shell_vertices(const Mesh& mesh, VertexId a, VertexId b, const Shell& shell, VertexList& list) {
  list.emplace_back(a);
  list.emplace_back(b);
  append_ring(mesh, a, b, shell, list);
}

}  // namespace metrica
