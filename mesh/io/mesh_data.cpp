#include <metrica/io/mesh_data.hpp>

namespace metrica::io {

const char* to_string(SolType t) {
  switch (t) {
    case SolType::scalar: return "scalar";
    case SolType::vector: return "vector";
    case SolType::sym_matrix: return "symmetric matrix";
    case SolType::matrix: return "matrix";
  }
  return "?";
}

std::vector<double> SolData::field(std::size_t k) const {
  const auto size = static_cast<std::size_t>(sol_type_size(types.at(k)));
  const auto off = static_cast<std::size_t>(offset(k));
  const auto st = static_cast<std::size_t>(stride());
  std::vector<double> out(count * size);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t c = 0; c < size; ++c) out[i * size + c] = values[i * st + off + c];
  return out;
}

}  // namespace metrica::io
