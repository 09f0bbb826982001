#include <metrica/distributed/part.hpp>

namespace metrica::distributed {

VertexIndex::VertexIndex(const std::vector<GlobalId>& ids) {
  sorted_.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) sorted_.emplace_back(ids[i], std::uint32_t(i));
  std::sort(sorted_.begin(), sorted_.end());
}

std::int64_t VertexIndex::find(GlobalId id) const {
  auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<GlobalId, std::uint32_t>{id, 0});
  if (it == sorted_.end() || it->first != id) return -1;
  return it->second;
}

}  // namespace metrica::distributed
