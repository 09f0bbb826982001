// Insertion of a vertex inside a tet (1 -> 4) or on a boundary face of a
// tet (1 -> 3, the face cut in three that keep its surface id): the
// insertions of the centroid rule (seed, section 3.2; the third, on an
// edge, is split_edge.hpp). Both are cavity replacements (cavity.hpp) of
// the one tet that contains the point, so they share its checks: the plan
// refuses anything but a re-triangulation of the same region.
//
// decide (pure, Precision): every child is positively oriented;
// apply: add the vertex, replace the tet.
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/cavity.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/predicates/precision.hpp>

#include <stdexcept>

namespace metrica {

// The children of tet t with p (to become vertex n) in place of each of
// its vertices; on a face split the vertex opposite the face is kept (its
// child would be flat).
inline void cell_children(const TetVertices& t, VertexId n, int kept_vertex, NewTets& out) {
  out.clear();
  for (int i = 0; i < 4; ++i) {
    if (i == kept_vertex) continue;
    TetVertices c = t;
    c[i] = n;
    out.emplace_back(c);
  }
}

// The children of t with the new vertex (kNoId) at p inside (face < 0)
// or on boundary face `face` (whose opposite vertex is kept). f(child
// vertices, child points) returns false to stop; then so does this.
template <class F>
bool all_cell_children(const Mesh& mesh, TetId t, int face, const Point& p, F&& f) {
  const auto& v = mesh.tet(t);
  for (int i = 0; i < 4; ++i) {
    if (i == face) continue;
    TetVertices c = v;
    TetPoints x = detail::tet_points(mesh, v);
    c[i] = kNoId;
    x[i] = p;
    if (!f(c, x)) return false;
  }
  return true;
}

// Decide: the children of t with p inside (face < 0) or on boundary face
// `face` are all positively oriented.
inline bool cell_split_is_valid(const Mesh& mesh, TetId t, int face, const Point& p) {
  return all_cell_children(mesh, t, face, p,
                           [](const TetVertices&, const TetPoints& x) { return positive_tet(x[0], x[1], x[2], x[3]); });
}

inline void preview_cell_split(const Mesh& mesh, TetId t, int face, const Point& p, PlannedTets& out) {
  out.clear();
  all_cell_children(mesh, t, face, p, [&](const TetVertices& c, const TetPoints& x) {
    out.push_back({c, x});
    return true;
  });
}

// Decide, criterion half: the children are accepted (the shape floor
// against t in t's metric, the criterion in the metric each child will
// have, the new vertex's `m` included: as split_accepted).
template <MetricSpace S, class Criterion>
bool cell_split_accepted(const Mesh& mesh, TetId t, int face, const Point& p, const VertexMetric& m,
                         const Acceptance<S, Criterion>& accept) {
  if (!accept.decides()) return true;
  const std::array<TetId, 1> parent{t};
  auto r = accept.replacing(mesh, parent);
  return all_cell_children(mesh, t, face, p, [&](const TetVertices& c, const TetPoints& x) {
    return r.admits_child(t, x, S::tet_metric_with(mesh, c, kNoId, m));
  });
}

struct CellSplitScratch {
  NewTets children;
  CavityPlan plan;
  TetList created;
};

// Apply: inserts a vertex at p with metric m inside t (face < 0) or on
// its boundary face `face` (checked by the caller: a boundary face with a
// surface id), and returns it.
inline VertexId split_cell(Mesh& mesh, TetId t, int face, const Point& p, const VertexMetric& m, CellSplitScratch& s) {
  const SurfaceId surface = face >= 0 ? mesh.surface_id(t, face) : 0;
  if (face >= 0 && (mesh.neighbour(t, face).valid() || surface <= 0)) return kNoId;
  const VertexId v = mesh.add_vertex(p);
  cell_children(mesh.tet(t), v, face, s.children);
  const std::array<TetId, 1> old{t};
  if (!plan_cavity(mesh, old, view(s.children), s.plan, kNoId, kNoId, surface))
    throw std::logic_error("split_cell: a 1-4 or 1-3 split that does not plan");
  set_vertex_metric(mesh, v, m);
  apply_cavity(mesh, old, view(s.children), s.plan, mesh.tet_ref(t), s.created);
  mesh.set_vertex_class(v, face >= 0 ? VertexClass::surface : VertexClass::interior);
  return v;
}

}  // namespace metrica
