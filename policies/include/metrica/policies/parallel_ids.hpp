// The ids of a parallel pass: each thread creates vertices and tets from
// its own pool of dead ids, topped up from a shared reserve by one atomic
// step per chunk, so that creating and removing takes no lock and no
// array is reallocated under a running thread. The reserve grows between
// rounds only (grow), when no thread runs. Vertices removed during the
// pass are recycled only after it: a thread may still hold a removed
// vertex's id in its work list. A removed tet's id may be reused at once
// by its thread: whoever still holds it as a seed peeks it, locks, and
// checks it again.
//
// Attached to the mesh for the pass (Mesh::attach_id_source) by the
// Speculative policy; each thread binds its pool (bind) before it works.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace metrica {

class ParallelIds final : public IdSource {
 public:
  // Attaches to `mesh` with its free lists plus `vertex_room` and
  // `tet_room` new dead ids in the reserve (the arrays grow in `run`'s
  // parts); `threads` pools.
  ParallelIds(Mesh& mesh, int threads, std::size_t vertex_room, std::size_t tet_room, const PartRunner& run);
  // Detaches, handing back every id not used (also on an exception).
  ~ParallelIds();
  ParallelIds(const ParallelIds&) = delete;
  ParallelIds& operator=(const ParallelIds&) = delete;

  // The pool the calling thread allocates from, until unbind.
  void bind(int thread);
  static void unbind();
  // Tops the calling thread's pool up to at least the given numbers of
  // ids; false when the reserve cannot (the caller waits for the next
  // round, after grow).
  bool fill(std::size_t vertices, std::size_t tets);
  // More room between rounds (no thread in the pass).
  void grow(std::size_t vertex_room, std::size_t tet_room);

  VertexId take_vertex() override;
  TetId take_tet() override;
  void give_vertex(VertexId v) override;
  void give_tet(TetId t) override;

 private:
  // One cache line (or more) each: every creation and removal writes its
  // thread's pool, which must not share a line with another's.
  struct alignas(64) Pool {
    std::vector<VertexId> vertices;
    std::vector<TetId> tets;
    std::vector<VertexId> removed_vertices;
    std::ptrdiff_t vertex_delta = 0, tet_delta = 0;
  };
  // Ids handed out from `cursor` on.
  struct Reserve {
    MeshArray<std::uint32_t> ids;
    std::atomic<std::size_t> cursor{0};
    bool take(std::vector<std::uint32_t>& out, std::size_t want);
    void drain_into(MeshArray<std::uint32_t>& out);
    void append(std::size_t first, std::size_t room, const PartRunner& run);
  };

  void detach() noexcept;

  Mesh& mesh_;
  PartRunner run_;
  std::vector<Pool> pools_;
  Reserve vertices_, tets_;
};

}  // namespace metrica
