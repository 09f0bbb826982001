#include <metrica/policies/parallel_ids.hpp>

#include <algorithm>
#include <stdexcept>

namespace metrica {

namespace {
// The pool of the calling thread while a parallel pass runs.
thread_local void* tls_pool = nullptr;

template <class Pool>
Pool& bound_pool() {
  if (!tls_pool) throw std::logic_error("ParallelIds: a thread without a pool creates or removes entities");
  return *static_cast<Pool*>(tls_pool);
}
}  // namespace

bool ParallelIds::Reserve::take(std::vector<std::uint32_t>& out, std::size_t want) {
  // Whole chunks: one atomic step per few thousand allocations.
  constexpr std::size_t kChunk = 1024;
  const std::size_t n = std::max(want, kChunk);
  const std::size_t first = cursor.fetch_add(n, std::memory_order_relaxed);
  if (first >= ids.size()) return false;
  const std::size_t last = std::min(first + n, ids.size());
  out.insert(out.end(), ids.begin() + static_cast<std::ptrdiff_t>(first),
             ids.begin() + static_cast<std::ptrdiff_t>(last));
  return last - first >= want;
}

void ParallelIds::Reserve::drain_into(MeshArray<std::uint32_t>& out) {
  const std::size_t first = std::min(cursor.load(), ids.size());
  out.insert(out.end(), ids.begin() + static_cast<std::ptrdiff_t>(first), ids.end());
  ids.clear();
  cursor = 0;
}

// Unused reserve first, then the new ids [first, first + room).
void ParallelIds::Reserve::append(std::size_t first, std::size_t room, const PartRunner& run) {
  MeshArray<std::uint32_t> fresh;
  drain_into(fresh);
  const std::size_t kept = fresh.size();
  fresh.resize(kept + room);
  const std::size_t parts = std::max<std::size_t>(run.parts, 1);
  run(parts, [&](std::size_t p) {
    const auto [lo, hi] = part_slice(room, parts, p);
    for (std::size_t i = lo; i < hi; ++i) fresh[kept + i] = static_cast<std::uint32_t>(first + i);
  });
  ids = std::move(fresh);
}

ParallelIds::ParallelIds(Mesh& mesh, int threads, std::size_t vertex_room, std::size_t tet_room, const PartRunner& run)
    : mesh_(mesh), run_(run), pools_(static_cast<std::size_t>(std::max(threads, 1))) {
  IdLedger free = mesh_.attach_id_source(*this);
  // The free lists first (the last freed handed out first), then as many
  // new ids as they lack.
  vertices_.ids.assign(free.free_vertices.rbegin(), free.free_vertices.rend());
  tets_.ids.assign(free.free_tets.rbegin(), free.free_tets.rend());
  const std::size_t free_v = free.free_vertices.size(), free_t = free.free_tets.size();
  try {
    grow(vertex_room > free_v ? vertex_room - free_v : 0, tet_room > free_t ? tet_room - free_t : 0);
  } catch (...) {
    detach();
    throw;
  }
}

ParallelIds::~ParallelIds() { detach(); }

void ParallelIds::detach() noexcept {
  IdLedger back;
  for (Pool& p : pools_) {
    back.free_vertices.insert(back.free_vertices.end(), p.vertices.begin(), p.vertices.end());
    back.free_vertices.insert(back.free_vertices.end(), p.removed_vertices.begin(), p.removed_vertices.end());
    back.free_tets.insert(back.free_tets.end(), p.tets.begin(), p.tets.end());
    back.vertex_delta += p.vertex_delta;
    back.tet_delta += p.tet_delta;
    // created = delta + removed, so created + removed = delta + 2 removed
    back.vertex_changes +=
        static_cast<std::uint64_t>(p.vertex_delta + 2 * static_cast<std::ptrdiff_t>(p.removed_vertices.size()));
  }
  pools_.clear();
  vertices_.drain_into(back.free_vertices);
  tets_.drain_into(back.free_tets);
  mesh_.detach_id_source(std::move(back));
}

void ParallelIds::grow(std::size_t vertex_room, std::size_t tet_room) {
  const DeadRoom room = mesh_.add_dead_room(vertex_room, tet_room, run_);
  vertices_.append(room.first_vertex, vertex_room, run_);
  tets_.append(room.first_tet, tet_room, run_);
}

void ParallelIds::bind(int thread) { tls_pool = &pools_[static_cast<std::size_t>(thread)]; }

void ParallelIds::unbind() { tls_pool = nullptr; }

bool ParallelIds::fill(std::size_t vertices, std::size_t tets) {
  Pool& pool = bound_pool<Pool>();
  bool ok = true;
  if (pool.vertices.size() < vertices) ok = vertices_.take(pool.vertices, vertices - pool.vertices.size()) && ok;
  if (pool.tets.size() < tets) ok = tets_.take(pool.tets, tets - pool.tets.size()) && ok;
  return ok;
}

VertexId ParallelIds::take_vertex() {
  Pool& pool = bound_pool<Pool>();
  if (pool.vertices.empty() && !fill(1, 0)) throw std::length_error("Mesh: parallel vertex reserve exhausted");
  const VertexId v = pool.vertices.back();
  pool.vertices.pop_back();
  ++pool.vertex_delta;
  return v;
}

TetId ParallelIds::take_tet() {
  Pool& pool = bound_pool<Pool>();
  if (pool.tets.empty() && !fill(0, 1)) throw std::length_error("Mesh: parallel tet reserve exhausted");
  const TetId t = pool.tets.back();
  pool.tets.pop_back();
  ++pool.tet_delta;
  return t;
}

void ParallelIds::give_vertex(VertexId v) {
  Pool& pool = bound_pool<Pool>();
  pool.removed_vertices.push_back(v);
  --pool.vertex_delta;
}

void ParallelIds::give_tet(TetId t) {
  Pool& pool = bound_pool<Pool>();
  pool.tets.push_back(t);
  --pool.tet_delta;
}

}  // namespace metrica
