// Replacing a cavity: a set of tets is removed and a set of new tets that
// covers the same region is glued in its place. Every reconnection of the
// seed is one such replacement: a 2-3 or 3-2 flip, the removal of an edge
// whose shell has n tets (4-4 and beyond), the 2-2 flip on the boundary,
// and the collapse of an edge (the ball of the removed vertex, renamed).
//
// plan_cavity is the topological half of "decide": it matches every face
// of the new tets with a face of the cavity's outer boundary (or with
// another new face) by vertex triple, and refuses a replacement that
// would leave a hole, glue three faces together or open the boundary.
// apply_cavity then writes the change (pure connectivity, the same code
// for every policy). The geometric half (positive orientation, criteria)
// is the operator's.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/small_vector.hpp>

#include <algorithm>
#include <cstdint>

namespace metrica {

using NewTets = boost::container::small_vector<TetVertices, 32>;

// Sign of the permutation taking tet t's stored order to (p0, p1, p2, p3):
// +1 when (p0..p3) is positively oriented like the stored tet.
inline int permutation_sign(const TetVertices& t, VertexId p0, VertexId p1, VertexId p2, VertexId p3) {
  const int idx[4] = {local_index(t, p0), local_index(t, p1), local_index(t, p2), local_index(t, p3)};
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += idx[i] > idx[j];
  return (inversions % 2 == 0) ? 1 : -1;
}

inline bool same_triangle(const TriangleVertices& x, const TriangleVertices& y) {
  return x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
}

struct CavityPlan {
  struct OuterFace {
    TriangleVertices key;   // sorted, after renaming
    FaceRef outside;        // neighbour outside the cavity, or none (boundary)
    SurfaceId surface = 0;  // its surface id: on the boundary, or an internal surface's
  };
  struct Entry {
    TriangleVertices key;
    int index;  // >= 0: outer face; < 0: new face -(4 * tet + face) - 1
  };
  // The faces with one triple: entries[first] alone (second < 0), or
  // entries[first] and entries[second] glued, first's index the smaller
  // (so a new face comes before an outer one).
  struct Match {
    int first, second;
    SurfaceId surface = 0;  // two new faces glued on an internal surface
  };
  // A face of an internal surface between two old tets that a collapse
  // carries to two new tets (its key after renaming).
  struct InnerSurfaceFace {
    TriangleVertices key;
    SurfaceId surface;
  };
  boost::container::small_vector<OuterFace, 64> outer;
  boost::container::small_vector<Entry, 160> entries;
  boost::container::small_vector<Match, 96> matches;
  boost::container::small_vector<InnerSurfaceFace, 16> inner_surface;
  SurfaceId new_boundary_surface = 0;
};

namespace detail {
// Groups plan.entries by triple into plan.matches, through an
// open-addressing table (linear in the faces, no sort of the triples).
// False when a triple appears more than twice.
inline bool match_faces(CavityPlan& plan) {
  const std::size_t n = plan.entries.size();
  std::size_t slots = 64;
  while (slots < 2 * n) slots *= 2;
  boost::container::small_vector<std::int32_t, 512> table(slots, -1);  // a match, or -1
  const std::size_t mask = slots - 1;
  plan.matches.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const TriangleVertices& k = plan.entries[i].key;
    std::size_t h = (k[0] * 0x9E3779B1u) ^ (k[1] * 0x85EBCA77u) ^ (k[2] * 0xC2B2AE3Du);
    h = (h ^ (h >> 15)) & mask;
    for (;; h = (h + 1) & mask) {
      const std::int32_t m = table[h];
      if (m < 0) {
        table[h] = static_cast<std::int32_t>(plan.matches.size());
        plan.matches.emplace_back(CavityPlan::Match{static_cast<int>(i), -1});
        break;
      }
      CavityPlan::Match& match = plan.matches[static_cast<std::size_t>(m)];
      if (!same_triangle(plan.entries[static_cast<std::size_t>(match.first)].key, k)) continue;
      if (match.second >= 0) return false;
      match.second = static_cast<int>(i);
      if (plan.entries[static_cast<std::size_t>(match.second)].index <
          plan.entries[static_cast<std::size_t>(match.first)].index)
        std::swap(match.first, match.second);
      break;
    }
  }
  return true;
}
}  // namespace detail

namespace detail {
// A face glued between two new tets takes the internal surface carried on
// its triple (a collapse); one between a new tet and the outside keeps the
// outer face's id. With `new_refs` (a collapse across regions), where
// neither carries an id the two sides must be one region: false when not.
inline bool carry_surface(const CavityPlan& plan, CavityPlan::Match& m, std::span<const int> new_refs,
                          const Mesh& mesh) {
  const auto& x = plan.entries[static_cast<std::size_t>(m.first)];
  const auto& y = plan.entries[static_cast<std::size_t>(m.second)];
  if (x.index >= 0) return true;  // two outer faces (the pinched case, checked by the caller)
  auto ref = [&](int index) { return new_refs[static_cast<std::size_t>((-index - 1) / 4)]; };
  if (y.index < 0) {
    for (const auto& carried : plan.inner_surface)
      if (same_triangle(carried.key, x.key)) {
        m.surface = carried.surface;
        return true;
      }
    return new_refs.empty() || ref(x.index) == ref(y.index);
  }
  const auto& o = plan.outer[static_cast<std::size_t>(y.index)];
  return new_refs.empty() || !o.outside.valid() || o.surface != 0 || ref(x.index) == mesh.tet_ref(o.outside.tet());
}
}  // namespace detail

// Plans replacing `old_tets` by `new_tets`, reading the old faces with
// vertex `from` renamed `to` (an edge collapse; kNoId for none). A new face
// that matches no outer face becomes a boundary face of surface
// `new_boundary_surface` when that is > 0 (the 2-2 flip), else the plan is
// refused. Internal surfaces are kept: a face of one between two old tets
// is refused, except in a collapse, which carries it to the two new tets
// with the renamed triple (or drops it with the collapsed edge), and in a
// replacement that remakes the surface (the interface 2-2 flip), which
// lists the surface's new faces between new tets in `surface_faces`. A
// replacement across regions gives each new tet's region in `new_refs`
// (empty: one region), and a new face between two regions must then be an
// internal surface's. False: the replacement is not a valid
// re-triangulation, or it would erase or mix those surfaces and regions.
inline bool plan_cavity(const Mesh& mesh, std::span<const TetId> old_tets, std::span<const TetVertices> new_tets,
                        CavityPlan& plan, VertexId from = kNoId, VertexId to = kNoId,
                        SurfaceId new_boundary_surface = 0, std::span<const int> new_refs = {},
                        std::span<const CavityPlan::InnerSurfaceFace> surface_faces = {}) {
  plan.outer.clear();
  plan.entries.clear();
  plan.inner_surface.assign(surface_faces.begin(), surface_faces.end());
  plan.new_boundary_surface = new_boundary_surface;
  auto in_cavity = [&](TetId t) { return std::find(old_tets.begin(), old_tets.end(), t) != old_tets.end(); };
  auto renamed = [&](TriangleVertices key) {
    for (auto& x : key)
      if (x == from) x = to;
    return sorted(key);
  };
  const bool internal = mesh.has_internal_surfaces();
  for (TetId t : old_tets) {
    const auto& v = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid() && in_cavity(n.tet())) {
        if (internal && mesh.internal_surface_id(t, f) != 0) {
          if (from == kNoId) {
            if (surface_faces.empty()) return false;
            continue;
          }
          const TriangleVertices key = renamed(face_vertices(v, f));
          if (t < n.tet() && key[0] != key[1] && key[1] != key[2])
            plan.inner_surface.emplace_back(CavityPlan::InnerSurfaceFace{key, mesh.internal_surface_id(t, f)});
        }
        continue;
      }
      const TriangleVertices key = renamed(face_vertices(v, f));
      if (key[0] == key[1] || key[1] == key[2]) {
        // The face shrinks to an edge: only a boundary face may vanish so
        // (the faces of a collapsed boundary edge).
        if (n.valid()) return false;
        continue;
      }
      plan.entries.emplace_back(CavityPlan::Entry{key, static_cast<int>(plan.outer.size())});
      plan.outer.emplace_back(CavityPlan::OuterFace{key, n, mesh.face_surface_id(t, f)});
    }
  }
  for (std::size_t k = 0; k < new_tets.size(); ++k)
    for (int f = 0; f < 4; ++f)
      plan.entries.emplace_back(
          CavityPlan::Entry{sorted(face_vertices(new_tets[k], f)), -static_cast<int>(4 * k + f) - 1});
  if (!detail::match_faces(plan)) return false;
  // Every triple must appear exactly twice, or once as a new face when the
  // replacement is allowed to make boundary faces.
  for (CavityPlan::Match& m : plan.matches) {
    const auto& x = plan.entries[static_cast<std::size_t>(m.first)];
    if (m.second < 0) {
      // Allowed only when the replacement remakes part of one surface
      // (the 2-2 flip): new boundary faces appear, old ones of that
      // surface vanish; the operator checks that they cover the same area.
      if (new_boundary_surface <= 0) return false;
      if (x.index >= 0 && (plan.outer[x.index].outside.valid() || plan.outer[x.index].surface != new_boundary_surface))
        return false;
    } else {
      const auto& y = plan.entries[static_cast<std::size_t>(m.second)];
      if ((!plan.inner_surface.empty() || !new_refs.empty()) && !detail::carry_surface(plan, m, new_refs, mesh))
        return false;
      if (x.index >= 0 && y.index >= 0) {
        // Two outer faces meet (the cavity of a collapse pinched to a
        // face): at most one of them may be a boundary face, and neither
        // an internal surface's.
        const auto& o1 = plan.outer[x.index];
        const auto& o2 = plan.outer[y.index];
        if (!o1.outside.valid() && !o2.outside.valid()) return false;
        if ((o1.outside.valid() && o1.surface != 0) || (o2.outside.valid() && o2.surface != 0)) return false;
      }
    }
  }
  // Every carried internal face found its two new tets.
  for (const auto& carried : plan.inner_surface) {
    bool found = false;
    for (const CavityPlan::Match& m : plan.matches)
      found = found || (m.surface == carried.surface &&
                        same_triangle(plan.entries[static_cast<std::size_t>(m.first)].key, carried.key));
    if (!found) return false;
  }
  return true;
}

// Applies a plan: removes the old tets, adds the new ones (their ids are
// written to `created`) in region `tet_ref` (or new_refs[k], as planned),
// links every face and keeps the vertex hints. The caller removes a vertex
// that no longer belongs to any tet.
template <class CreatedList>
void apply_cavity(Mesh& mesh, std::span<const TetId> old_tets, std::span<const TetVertices> new_tets,
                  const CavityPlan& plan, int tet_ref, CreatedList& created, std::span<const int> new_refs = {}) {
  for (TetId t : old_tets) mesh.remove_tet(t);
  created.clear();
  for (std::size_t k = 0; k < new_tets.size(); ++k) {
    const auto& v = new_tets[k];
    const TetId t = mesh.add_tet(v, new_refs.empty() ? tet_ref : new_refs[k]);
    created.emplace_back(t);
    for (VertexId x : v) mesh.set_vert2tet(x, t);
  }
  auto new_face = [&](int index) {
    const int code = -index - 1;
    return FaceRef(created[static_cast<std::size_t>(code / 4)], code % 4);
  };
  // Two outer faces glued (a pinched collapse) re-point their vertices'
  // hints at the tet kept; done last, in the order of their triples, so
  // the hints do not depend on the table's order.
  boost::container::small_vector<const CavityPlan::Match*, 8> glued;
  for (const CavityPlan::Match& m : plan.matches) {
    const auto& x = plan.entries[static_cast<std::size_t>(m.first)];
    if (m.second < 0) {
      if (x.index >= 0) continue;  // an old boundary face that the new ones replace
      const FaceRef f = new_face(x.index);
      mesh.set_neighbour(f.tet(), f.face(), FaceRef::none());
      mesh.set_surface_id(f.tet(), f.face(), plan.new_boundary_surface);
      continue;
    }
    const auto& y = plan.entries[static_cast<std::size_t>(m.second)];
    // The smaller index first: a new face (negative) comes first.
    if (x.index < 0 && y.index < 0) {
      mesh.link(new_face(x.index), new_face(y.index));
      if (m.surface != 0) {
        mesh.set_internal_surface_id(new_face(x.index).tet(), new_face(x.index).face(), m.surface);
        mesh.set_internal_surface_id(new_face(y.index).tet(), new_face(y.index).face(), m.surface);
      }
    } else if (x.index < 0) {
      const FaceRef f = new_face(x.index);
      const auto& o = plan.outer[y.index];
      if (o.outside.valid()) {
        mesh.link(f, o.outside);
        if (o.surface != 0) mesh.set_internal_surface_id(f.tet(), f.face(), o.surface);
      } else {
        mesh.set_neighbour(f.tet(), f.face(), FaceRef::none());
        mesh.set_surface_id(f.tet(), f.face(), o.surface);
      }
    } else {
      const auto& o1 = plan.outer[x.index];
      const auto& o2 = plan.outer[y.index];
      if (o1.outside.valid() && o2.outside.valid()) {
        mesh.link(o1.outside, o2.outside);
      } else {
        const auto& in = o1.outside.valid() ? o1 : o2;
        const auto& bd = o1.outside.valid() ? o2 : o1;
        mesh.set_neighbour(in.outside.tet(), in.outside.face(), FaceRef::none());
        mesh.set_surface_id(in.outside.tet(), in.outside.face(), bd.surface);
      }
      glued.emplace_back(&m);
    }
  }
  auto key_of = [&](const CavityPlan::Match* m) -> const TriangleVertices& {
    return plan.entries[static_cast<std::size_t>(m->first)].key;
  };
  std::sort(glued.begin(), glued.end(),
            [&](const CavityPlan::Match* a, const CavityPlan::Match* b) { return key_of(a) < key_of(b); });
  for (const CavityPlan::Match* m : glued) {
    const auto& o1 = plan.outer[plan.entries[static_cast<std::size_t>(m->first)].index];
    const auto& o2 = plan.outer[plan.entries[static_cast<std::size_t>(m->second)].index];
    const FaceRef keep = o1.outside.valid() ? o1.outside : o2.outside;
    for (VertexId v : key_of(m)) mesh.set_vert2tet(v, keep.tet());
  }
}

}  // namespace metrica
