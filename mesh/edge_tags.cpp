#include <metrica/edge_tags.hpp>

#include <mutex>

namespace metrica {

bool EdgeTags::is_ridge(VertexId a, VertexId b) const {
  std::lock_guard guard(lock_);
  return ridges_.count(edge_key(a, b)) != 0;
}

bool EdgeTags::is_required(VertexId a, VertexId b) const {
  std::lock_guard guard(lock_);
  return required_.count(edge_key(a, b)) != 0;
}

void EdgeTags::split(VertexId a, VertexId b, VertexId m) {
  std::lock_guard guard(lock_);
  for (Set* tags : {&ridges_, &features_}) {
    if (tags->erase(edge_key(a, b))) {
      tags->insert(edge_key(a, m));
      tags->insert(edge_key(m, b));
    }
  }
}

void EdgeTags::merge(VertexId from, VertexId to, std::span<const VertexId> neighbours) {
  std::lock_guard guard(lock_);
  for (Set* tags : {&ridges_, &features_}) {
    for (VertexId x : neighbours)
      if (tags->erase(edge_key(from, x)) && x != to) tags->insert(edge_key(to, x));
  }
}

void EdgeTags::renumber(std::span<const VertexId> new_id) {
  for (Set* tags : {&ridges_, &features_, &required_}) {
    Set out;
    out.reserve(tags->size());
    for (auto key : *tags) {
      const auto e = edge_from_key(key);
      if (new_id[e[0]] != kNoId && new_id[e[1]] != kNoId) out.insert(edge_key(new_id[e[0]], new_id[e[1]]));
    }
    *tags = std::move(out);
  }
}

}  // namespace metrica
