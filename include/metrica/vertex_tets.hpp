// Vertex-to-tet incidence in compressed rows (CSR): the tets around every
// vertex, built in two passes over the tets with no per-vertex allocation.
// A snapshot: operators that change the mesh walk adjacency instead.
#pragma once

#include <metrica/mesh.hpp>

#include <span>
#include <vector>

namespace metrica {

class VertexTets {
 public:
  explicit VertexTets(const Mesh& mesh) : offsets_(mesh.vertex_capacity() + 1, 0) {
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t))
        for (VertexId v : mesh.tet(t)) ++offsets_[v + 1];
    for (std::size_t v = 0; v + 1 < offsets_.size(); ++v) offsets_[v + 1] += offsets_[v];
    tets_.resize(offsets_.back());
    std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t))
        for (VertexId v : mesh.tet(t)) tets_[fill[v]++] = t;
  }

  std::span<const TetId> of(VertexId v) const { return {tets_.data() + offsets_[v], offsets_[v + 1] - offsets_[v]}; }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<TetId> tets_;
};

}  // namespace metrica
