#include <metrica/distributed/part.hpp>

namespace metrica::distributed {

VertexIndex::VertexIndex(const std::vector<GlobalId>& ids) {
  std::size_t size = 4;
  int bits = 2;
  while (size < ids.size() + ids.size() / 2) size *= 2, ++bits;
  keys_.assign(size, kEmpty);
  places_.assign(size, 0);
  mask_ = size - 1;
  shift_ = 64 - bits;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0) continue;
    std::size_t s = slot(ids[i]);
    while (keys_[s] != kEmpty && keys_[s] != ids[i]) s = (s + 1) & mask_;
    if (keys_[s] == kEmpty) keys_[s] = ids[i], places_[s] = std::uint32_t(i);
  }
}

}  // namespace metrica::distributed
