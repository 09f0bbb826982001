#include <metrica/error.hpp>
#include <metrica/io/mesh_data.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

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

void check_finite(const MeshData& m, const std::string& path) {
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    if (!m.vertices[v].allFinite())
      throw IoError(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}); nothing written", path,
                                numbered(v), m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z()));
  for (const auto& list : m.on_geometry)
    for (std::size_t i = 0; i < list.size(); ++i)
      if (!std::isfinite(list[i].u) || !std::isfinite(list[i].v) || !std::isfinite(list[i].dist))
        throw IoError(fmt::format("{}: the model parameters of vertex {} are not finite; nothing written", path,
                                  numbered(list[i].vertex)));
}

void check_finite(const SolData& s, const std::string& path) {
  const auto stride = static_cast<std::size_t>(std::max(1, s.stride()));
  for (std::size_t i = 0; i < s.values.size(); ++i)
    if (!std::isfinite(s.values[i]))
      throw IoError(fmt::format("{}: the value at vertex {} is not finite ({}); nothing written", path,
                                numbered(i / stride), s.values[i]));
}

}  // namespace metrica::io
