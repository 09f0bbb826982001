// The tagged edges of a mesh: its ridges (from classification), the
// feature edges the input gave (Edges / Ridges keywords) and the required
// edges (RequiredEdges, the edges of RequiredTriangles, kept as they
// are), each a set of edge keys. Safe to read and update from several threads at once: the
// operations of a parallel pass put vertices on ridges and collapse
// along them, so each call takes a short spin lock (a hash-set lookup,
// cheaper than an OS mutex). The whole sets only while no thread runs.
#pragma once

#include <metrica/ids.hpp>
#include <metrica/spin_lock.hpp>
#include <metrica/tet_topology.hpp>

#include <cstdint>
#include <span>
#include <unordered_set>

namespace metrica {

class EdgeTags {
 public:
  using Set = std::unordered_set<std::uint64_t>;

  bool is_ridge(VertexId a, VertexId b) const;
  bool is_required(VertexId a, VertexId b) const;
  // Replaces ab by am and mb in both sets (m put on ab).
  void split(VertexId a, VertexId b, VertexId m);
  // Edges (from, x) become (to, x) and (from, to) goes, for the x given.
  void merge(VertexId from, VertexId to, std::span<const VertexId> neighbours);

  const Set& ridges() const { return ridges_; }
  const Set& features() const { return features_; }
  const Set& required() const { return required_; }
  // Whether a feature edge was ever added: read without the lock (only
  // add_feature writes it, never during a parallel pass).
  bool has_features() const { return ever_features_; }
  void set_ridges(Set ridges) { ridges_ = std::move(ridges); }
  void add_feature(VertexId a, VertexId b) {
    features_.insert(edge_key(a, b));
    ever_features_ = true;
  }
  void add_required(VertexId a, VertexId b) { required_.insert(edge_key(a, b)); }
  // Renames every vertex v to new_id[v], dropping edges with an end
  // mapped to kNoId (compaction).
  void renumber(std::span<const VertexId> new_id);

 private:
  Set ridges_, features_;
  Set required_;                // never split nor merged: both ends are required vertices
  bool ever_features_ = false;  // a feature edge was ever added
  mutable SpinLock lock_;
};

}  // namespace metrica
