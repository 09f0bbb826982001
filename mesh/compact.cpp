// Mesh::compact(): drop dead entities and renumber for locality.
//
// Vertices are sorted along a Morton (Z-order) curve of their positions,
// tets by their smallest new vertex id, so that a walk through the mesh
// touches nearby memory. Morton rather than Hilbert: one line of bit
// interleaving, and within a few percent of Hilbert's cache behaviour on
// tet meshes.
#include <metrica/allocator.hpp>
#include <metrica/bucket_cursors.hpp>
#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <utility>

namespace metrica {
namespace {

// Spreads the low 21 bits of x so that two zero bits separate each.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// Turns key[i] (below `keys`, or kNoId) into i's place in the order of
// the items by key, ties in order of i, in place: a stable counting sort
// in run.parts parts (bucket_cursors), the order of one thread for any
// number of parts; returns the number of items with a key. It was one
// thread's two passes over the tets in each compaction (with the gathers'
// value-initialisation, 20 of the 110 one-thread samples of a 2-thread
// adaptation at 0.94M tets). In place, so that no order array stands
// beside the mesh's arrays at compaction, the passes' peak.
std::size_t ranks_by_key(std::span<VertexId> key, std::size_t keys, const PartRunner& run) {
  const std::size_t parts = std::max<std::size_t>(run.parts, 1), n = key.size();
  MeshArray<std::uint32_t> cursor, start;  // cursor[p * keys + k]
  const std::size_t ranked = bucket_cursors(
      n, keys, parts,
      [&](std::size_t i, auto&& add) {
        if (key[i] != kNoId) add(key[i]);
      },
      run, cursor, start);
  run(parts, [&](std::size_t p) {
    std::uint32_t* next = cursor.data() + p * keys;
    const auto [first, last] = part_slice(n, parts, p);
    for (std::size_t i = first; i < last; ++i)
      if (key[i] != kNoId) key[i] = next[key[i]]++;
  });
  return ranked;
}

}  // namespace

void Mesh::compact() { compact(PartRunner{}); }

void Mesh::compact(const PartRunner& given) {
  PartRunner run = given;
  run.parts = std::max<std::size_t>(run.parts, 1);
  const std::size_t parts = run.parts;
  const std::size_t vcap = vertex_capacity(), tcap = tet_capacity();

  // Bounding box and live vertices, per part.
  struct alignas(64) PartBox {
    Point lo = Point::Constant(std::numeric_limits<double>::max());
    Point hi = Point::Constant(-std::numeric_limits<double>::max());
    std::size_t live = 0;
  };
  std::vector<PartBox> boxes(parts);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(vcap, parts, p);
    PartBox b;
    for (std::size_t v = first; v < last; ++v) {
      if (!vertex_alive(static_cast<VertexId>(v))) continue;
      b.lo = b.lo.cwiseMin(points_[v]);
      b.hi = b.hi.cwiseMax(points_[v]);
      ++b.live;
    }
    boxes[p] = b;
  });
  PartBox all;
  std::vector<std::size_t> offset(parts + 1, 0);
  for (std::size_t p = 0; p < parts; ++p) {
    all.lo = all.lo.cwiseMin(boxes[p].lo);
    all.hi = all.hi.cwiseMax(boxes[p].hi);
    offset[p + 1] = offset[p] + boxes[p].live;
  }
  const std::size_t nv = offset[parts];

  // Vertices along the Morton curve of the bounding box, sorted as (code,
  // id) pairs, which sit together in memory (comparing through a code
  // array missed the cache at every step); ids break ties, so the order
  // is the same for any number of parts.
  const Point lo = all.lo;
  const Point scale = ((all.hi - all.lo).array().max(1e-300).inverse() * double((1u << 21) - 1)).matrix();
  struct Keyed {
    std::uint64_t code;
    VertexId v;
    bool operator<(const Keyed& o) const { return code < o.code || (code == o.code && v < o.v); }
  };
  MeshArray<Keyed> keyed;
  keyed.resize(nv);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(vcap, parts, p);
    std::size_t i = offset[p];
    for (std::size_t v = first; v < last; ++v) {
      if (!vertex_alive(static_cast<VertexId>(v))) continue;
      const Point q = (points_[v] - lo).cwiseProduct(scale);
      const std::uint64_t code = spread_bits(std::uint64_t(q.x())) | spread_bits(std::uint64_t(q.y())) << 1 |
                                 spread_bits(std::uint64_t(q.z())) << 2;
      keyed[i++] = {code, static_cast<VertexId>(v)};
    }
  });
  sort_in_parts(keyed.begin(), keyed.end(), std::less<>{}, parts, run);
  std::vector<VertexId> new_vertex(vcap, kNoId);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(nv, parts, p);
    for (std::size_t i = first; i < last; ++i) new_vertex[keyed[i].v] = static_cast<VertexId>(i);
  });
  keyed = {};

  // Tets by their smallest new vertex id, ties in id order: a counting
  // sort on the key (it is below the vertex count), which keeps the id
  // order within a key, in parts (ranks_by_key).
  MeshArray<TetId> new_tet;  // each tet's key, then its new id
  new_tet.resize(tcap);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(tcap, parts, p);
    for (std::size_t t = first; t < last; ++t) {
      VertexId key = kNoId;
      if (!tet_alive(static_cast<TetId>(t))) {
        new_tet[t] = key;
        continue;
      }
      for (VertexId v : tets_[t]) {
        if (v >= new_vertex.size() || new_vertex[v] == kNoId)
          throw std::logic_error("Mesh::compact: a live tet has a dead or unknown vertex");
        key = std::min(key, new_vertex[v]);
      }
      new_tet[t] = key;
    }
  });
  const std::size_t live = ranks_by_key(new_tet, nv, run);

  permute_to(points_, new_vertex, nv, run);
  permute_to(vertex_ref_, new_vertex, nv, run);
  permute_to(vert2tet_, new_vertex, nv, run);
  permute_to(vertex_class_, new_vertex, nv, run);
  permute_to(vertex_flags_, new_vertex, nv, run);
  permute_to(vertex_stamp_, new_vertex, nv, run);
  attributes_.vertices.renumber(new_vertex, nv, run);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(nv, parts, p);
    for (std::size_t v = first; v < last; ++v) vert2tet_[v] = vert2tet_[v] < tcap ? new_tet[vert2tet_[v]] : kNoId;
  });

  permute_to(tets_, new_tet, live, run);
  permute_to(tet2tets_, new_tet, live, run);
  permute_to(tet_ref_, new_tet, live, run);
  permute_to(tet_stamp_, new_tet, live, run);
  attributes_.tets.renumber(new_tet, live, run);
  attributes_.refresh();
  if (has_internal_surfaces()) permute_to(internal_, new_tet, live, run);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(live, parts, p);
    for (std::size_t t = first; t < last; ++t) {
      for (auto& v : tets_[t]) v = new_vertex[v];
      for (auto& n : tet2tets_[t])
        if (n.valid()) n = FaceRef(new_tet[n.tet()], n.face());
    }
  });

  edge_tags_.renumber(new_vertex);
  // Required vertices are never removed: each triangle keeps its three.
  for (auto& tri : required_triangles_) {
    for (auto& v : tri) v = new_vertex[v];
    std::sort(tri.begin(), tri.end());
  }
  std::sort(required_triangles_.begin(), required_triangles_.end());
  free_vertices_.clear();
  free_tets_.clear();
  live_vertices_ = nv;
  live_tets_ = live;
  ++renumberings_;
}

}  // namespace metrica
