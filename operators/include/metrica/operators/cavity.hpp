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

#include <boost/container/small_vector.hpp>

#include <algorithm>

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
    SurfaceId surface = 0;  // its surface id when on the boundary
  };
  struct Entry {
    TriangleVertices key;
    int index;  // >= 0: outer face; < 0: new face -(4 * tet + face) - 1
  };
  boost::container::small_vector<OuterFace, 64> outer;
  boost::container::small_vector<Entry, 160> entries;
  SurfaceId new_boundary_surface = 0;
};

// Plans replacing `old_tets` by `new_tets`, reading the old faces with
// vertex `from` renamed `to` (an edge collapse; kNoId for none). A new face
// that matches no outer face becomes a boundary face of surface
// `new_boundary_surface` when that is > 0 (the 2-2 flip), else the plan is
// refused. False: the replacement is not a valid re-triangulation.
inline bool plan_cavity(const Mesh& mesh, std::span<const TetId> old_tets, std::span<const TetVertices> new_tets,
                        CavityPlan& plan, VertexId from = kNoId, VertexId to = kNoId,
                        SurfaceId new_boundary_surface = 0) {
  plan.outer.clear();
  plan.entries.clear();
  plan.new_boundary_surface = new_boundary_surface;
  auto in_cavity = [&](TetId t) { return std::find(old_tets.begin(), old_tets.end(), t) != old_tets.end(); };
  for (TetId t : old_tets) {
    const auto& v = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid() && in_cavity(n.tet())) continue;
      TriangleVertices key = face_vertices(v, f);
      for (auto& x : key)
        if (x == from) x = to;
      key = sorted(key);
      if (key[0] == key[1] || key[1] == key[2]) {
        // The face shrinks to an edge: only a boundary face may vanish so
        // (the faces of a collapsed boundary edge).
        if (n.valid()) return false;
        continue;
      }
      plan.entries.push_back({key, static_cast<int>(plan.outer.size())});
      plan.outer.push_back({key, n, n.valid() ? 0 : mesh.surface_id(t, f)});
    }
  }
  for (std::size_t k = 0; k < new_tets.size(); ++k)
    for (int f = 0; f < 4; ++f)
      plan.entries.push_back({sorted(face_vertices(new_tets[k], f)), -static_cast<int>(4 * k + f) - 1});
  // Triples compared element by element (std::array's operators go
  // through memcmp, a call per comparison: 1.4% of an adaptation).
  std::sort(plan.entries.begin(), plan.entries.end(), [](const CavityPlan::Entry& x, const CavityPlan::Entry& y) {
    if (x.key[0] != y.key[0]) return x.key[0] < y.key[0];
    if (x.key[1] != y.key[1]) return x.key[1] < y.key[1];
    if (x.key[2] != y.key[2]) return x.key[2] < y.key[2];
    return x.index < y.index;
  });
  // Every triple must appear exactly twice, or once as a new face when the
  // replacement is allowed to make boundary faces.
  for (std::size_t i = 0; i < plan.entries.size();) {
    std::size_t j = i + 1;
    while (j < plan.entries.size() && same_triangle(plan.entries[j].key, plan.entries[i].key)) ++j;
    const std::size_t count = j - i;
    if (count == 1) {
      // Allowed only when the replacement remakes part of one surface
      // (the 2-2 flip): new boundary faces appear, old ones of that
      // surface vanish; the operator checks that they cover the same area.
      const auto& x = plan.entries[i];
      if (new_boundary_surface <= 0) return false;
      if (x.index >= 0 && (plan.outer[x.index].outside.valid() || plan.outer[x.index].surface != new_boundary_surface))
        return false;
    } else if (count == 2) {
      const auto& x = plan.entries[i];
      const auto& y = plan.entries[i + 1];
      if (x.index >= 0 && y.index >= 0) {
        // Two outer faces meet (the cavity of a collapse pinched to a
        // face): at most one of them may be a boundary face.
        if (!plan.outer[x.index].outside.valid() && !plan.outer[y.index].outside.valid()) return false;
      }
    } else {
      return false;
    }
    i = j;
  }
  return true;
}

// Applies a plan: removes the old tets, adds the new ones (their ids are
// written to `created`), links every face and keeps the vertex hints. The
// caller removes a vertex that no longer belongs to any tet.
template <class CreatedList>
void apply_cavity(Mesh& mesh, std::span<const TetId> old_tets, std::span<const TetVertices> new_tets,
                  const CavityPlan& plan, int tet_ref, CreatedList& created) {
  for (TetId t : old_tets) mesh.remove_tet(t);
  created.clear();
  for (const auto& v : new_tets) {
    const TetId t = mesh.add_tet(v, tet_ref);
    created.push_back(t);
    for (VertexId x : v) mesh.set_vert2tet(x, t);
  }
  auto new_face = [&](int index) {
    const int code = -index - 1;
    return FaceRef(created[static_cast<std::size_t>(code / 4)], code % 4);
  };
  for (std::size_t i = 0; i < plan.entries.size();) {
    std::size_t j = i + 1;
    while (j < plan.entries.size() && same_triangle(plan.entries[j].key, plan.entries[i].key)) ++j;
    const auto& x = plan.entries[i];
    if (j - i == 1) {
      if (x.index >= 0) {  // an old boundary face that the new ones replace
        i = j;
        continue;
      }
      const FaceRef f = new_face(x.index);
      mesh.set_neighbour(f.tet(), f.face(), FaceRef::none());
      mesh.set_surface_id(f.tet(), f.face(), plan.new_boundary_surface);
    } else {
      const auto& y = plan.entries[i + 1];
      // Sorted by index: a new face (negative) comes first.
      if (x.index < 0 && y.index < 0) {
        mesh.link(new_face(x.index), new_face(y.index));
      } else if (x.index < 0) {
        const FaceRef f = new_face(x.index);
        const auto& o = plan.outer[y.index];
        if (o.outside.valid()) {
          mesh.link(f, o.outside);
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
        const FaceRef keep = o1.outside.valid() ? o1.outside : o2.outside;
        for (VertexId v : x.key) mesh.set_vert2tet(v, keep.tet());
      }
    }
    i = j;
  }
}

}  // namespace metrica
