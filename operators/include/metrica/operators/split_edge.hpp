// Insertion of a vertex on an edge: every tet of the edge's shell is cut in
// two (seed, section 3.2's insertion by split; the edge-based rule of Mmg,
// Omega_h and refine). Boundary and internal-surface faces of the shell
// are cut too and keep their surface ids; a ridge edge becomes two ridge edges and the new
// vertex is a ridge vertex, so the classification stays up to date.
//
// The topology (apply) is one function for every policy; the geometric
// check (decide) that no child is flat or inverted is a Precision template.
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/predicates/precision.hpp>

namespace metrica {

// The children of the shell's tets with the new vertex at p (vertex id
// kNoId): for each tet, the one with b replaced, then the one with a.
// f(parent, child vertices, child points) returns false to stop; then so
// does this.
template <class F>
bool all_split_children(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, const Point& p, F&& f) {
  for (TetId t : shell.tets) {
    const auto& v = mesh.tet(t);
    for (VertexId gone : {b, a}) {
      TetVertices c = v;
      TetPoints x = detail::tet_points(mesh, v);
      const int i = local_index(v, gone);
      c[i] = kNoId;
      x[i] = p;
      if (!f(t, c, x)) return false;
    }
  }
  return true;
}

// Decide: both children of every shell tet are positively oriented with m
// at p. Pure: reads the mesh, writes nothing.
inline bool split_is_valid(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, const Point& p) {
  return all_split_children(mesh, shell, a, b, p, [](TetId, const TetVertices&, const TetPoints& x) {
    return positive_tet(x[0], x[1], x[2], x[3]);
  });
}

inline void preview_split(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, const Point& p,
                          PlannedTets& out) {
  out.clear();
  all_split_children(mesh, shell, a, b, p, [&](TetId, const TetVertices& c, const TetPoints& x) {
    out.push_back({c, x});
    return true;
  });
}

// Decide, criterion half: the children are accepted (the shape floor
// against each child's parent, in the parent's metric; the criterion
// against the shell, in the metric each child will have, the new vertex's
// `m` included: Acceptance::admits_child).
template <MetricSpace S, class Criterion>
bool split_accepted(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, const Point& p,
                    const VertexMetric& m, const Acceptance<S, Criterion>& accept) {
  if (!accept.decides()) return true;
  auto r = accept.replacing(mesh, view(shell.tets));
  return all_split_children(mesh, shell, a, b, p, [&](TetId t, const TetVertices& c, const TetPoints& x) {
    return r.admits_child(t, x, S::tet_metric_with(mesh, c, kNoId, m));
  });
}

// Apply: inserts the vertex at p with metric `m` on edge ab (shell from
// edge_shell) and returns it. Each shell tet keeps its id with b replaced
// by the new vertex; its twin with a replaced is a new tet. Local vertex
// order is kept, so every face index carries over to the children.
inline VertexId split_edge(Mesh& mesh, const Shell& shell, VertexId a, VertexId b, const Point& p,
                           const VertexMetric& m) {
  const VertexId n = mesh.add_vertex(p);
  set_vertex_metric(mesh, n, m);
  boost::container::small_vector<TetId, 64> twin(shell.tets.size());
  auto twin_of = [&](TetId t) {
    for (std::size_t k = 0; k < shell.tets.size(); ++k)
      if (shell.tets[k] == t) return twin[k];
    return kNoId;
  };
  for (std::size_t k = 0; k < shell.tets.size(); ++k) {
    const TetId t = shell.tets[k];
    TetVertices v2 = mesh.tet(t);
    v2[local_index(v2, a)] = n;
    twin[k] = mesh.add_tet(v2, mesh.tet_ref(t));
  }
  const bool internal = mesh.has_internal_surfaces();
  bool on_internal = false;  // the edge lies on an internal surface
  for (std::size_t k = 0; k < shell.tets.size(); ++k) {
    const TetId t1 = shell.tets[k], t2 = twin[k];
    const TetVertices old = mesh.tet(t1);
    const int ia = local_index(old, a), ib = local_index(old, b);
    // Internal-surface faces: t2 takes t1's face opposite a and both halves
    // of the faces through the edge; the face between t1 and t2 is new.
    if (internal) {
      for (int f = 0; f < 4; ++f) {
        const SurfaceId id = mesh.internal_surface_id(t1, f);
        if (f == ib || id == 0) continue;
        mesh.set_internal_surface_id(t2, f, id);
        if (f != ia) on_internal = true;
      }
      mesh.set_internal_surface_id(t1, ia, 0);
    }
    // Outer faces: opposite b for t1 (it holds a), opposite a for t2.
    const FaceRef out_a = mesh.neighbour(t1, ia);
    const SurfaceId sid_a = mesh.surface_id(t1, ia);
    if (out_a.valid())
      mesh.link(FaceRef(t2, ia), out_a);
    else
      mesh.set_surface_id(t2, ia, sid_a);
    mesh.link(FaceRef(t1, ia), FaceRef(t2, ib));  // t1 keeps its face opposite b as it was
    // The two faces through the edge: neighbours are shell tets, whose
    // children pair up the same way; on the boundary both children keep
    // the surface id.
    for (int f = 0; f < 4; ++f) {
      if (f == ia || f == ib) continue;
      const FaceRef nb = mesh.neighbour(t1, f);
      if (nb.valid()) {
        mesh.set_neighbour(t2, f, FaceRef(twin_of(nb.tet()), nb.face()));
      } else {
        mesh.set_surface_id(t2, f, mesh.surface_id(t1, f));
      }
    }
    TetVertices v1 = old;
    v1[ib] = n;
    mesh.set_tet_vertices(t1, v1);
  }
  mesh.set_vert2tet(n, shell.tets.front());
  mesh.set_vert2tet(b, twin.front());  // the other shell vertices are in both children
  if (mesh.is_ridge(a, b))
    mesh.set_vertex_class(n, VertexClass::ridge);
  else if (!shell.closed || on_internal)
    mesh.set_vertex_class(n, VertexClass::surface);
  if (on_internal) mesh.set_on_internal_surface(n, true);
  mesh.split_ridge(a, b, n);
  return n;
}

}  // namespace metrica
