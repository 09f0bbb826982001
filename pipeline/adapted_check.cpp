#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

namespace metrica {

double adapted_volume_tolerance(int iterations, double volume_budget) {
  const double budget = iterations * volume_budget;
  return budget * (1.0 + budget) + 1e-9;
}

void require_adapted(const Mesh& mesh, const CadModel* model, double volume, double relative_tolerance,
                     const PartRunner& sweeps) {
  ValidateOptions vo;
  vo.run = sweeps;
  if (!model) {
    vo.expected_volume = volume;
    vo.volume_tolerance = relative_tolerance;
  }
  const auto check = mesh.validate(vo);
  if (!check.ok())
    throw NotAdapted(fmt::format("adapt: the adapted mesh is invalid; nothing written\n{}", check.to_string()));
  if (!model) return;
  try {
    require_on_model(mesh, *model, "adapt");
  } catch (const InputError& e) {
    throw NotAdapted(e.what());
  }
}

}  // namespace metrica
