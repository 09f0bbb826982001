// Where the mesh takes the ids of new entities and puts those of removed
// ones while a concurrency policy runs a parallel pass. The threads of a
// pass must neither share the mesh's free lists nor grow its arrays, so
// the policy attaches a source for the pass (Mesh::attach_id_source) and
// the mesh's own free lists and counts wait until it detaches. The
// Speculative policy's source is a pool per thread fed from a shared
// reserve (policies/parallel_ids.hpp); the core knows only this
// interface.
#pragma once

#include <metrica/ids.hpp>
#include <metrica/mesh_array.hpp>

#include <cstddef>
#include <cstdint>

namespace metrica {

// Called by add_vertex, add_tet, remove_vertex and remove_tet, from any
// thread of the pass; a source that cannot give an id throws.
class IdSource {
 public:
  virtual VertexId take_vertex() = 0;
  virtual TetId take_tet() = 0;
  virtual void give_vertex(VertexId v) = 0;
  virtual void give_tet(TetId t) = 0;

 protected:
  ~IdSource() = default;
};

// What a source gets when attached (the free lists, emptied in the mesh)
// and gives back when detached: every id it still holds, and the counts
// of what its pass did.
struct IdLedger {
  MeshArray<VertexId> free_vertices;
  MeshArray<TetId> free_tets;
  std::ptrdiff_t vertex_delta = 0;   // vertices created minus removed
  std::ptrdiff_t tet_delta = 0;      // tets created minus removed
  std::uint64_t vertex_changes = 0;  // vertices created plus removed
};

// The first id of each kind of the dead room Mesh::add_dead_room appended.
struct DeadRoom {
  std::size_t first_vertex = 0, first_tet = 0;
};

}  // namespace metrica
