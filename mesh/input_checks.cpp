#include <metrica/error.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/numbering.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica {

void check_coordinates(const io::MeshData& data, const std::string& source) {
  for (std::size_t v = 0; v < data.vertices.size(); ++v) {
    const Point& p = data.vertices[v];
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) <= kCoordinateLimit))
        throw InputError(
            fmt::format("{}: vertex {} has coordinates ({}, {}, {}): each must be finite and within "
                        "+-{:g}",
                        source, numbered(v), p.x(), p.y(), p.z(), kCoordinateLimit));
  }
}

void check_valid_input(const Mesh& mesh, const std::string& source) {
  ValidateOptions vo;
  vo.max_messages_per_check = 3;
  const auto report = mesh.validate(vo);
  if (report.ok()) return;
  throw InputError(fmt::format("{}: the input mesh is invalid (run `metrica check {}` for every problem)\n{}", source,
                               source, report.to_string()));
}

}  // namespace metrica
