// What an adapted mesh must be before it is written or handed back: valid,
// of the input's volume within what the adaptations may change (without a
// model) and on the model (with one). The command, the loop and the Python
// module share these checks.
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

namespace metrica {

// The relative change of volume `iterations` adaptations may make, each
// within its AdaptOptions::volume_budget of the volume it starts from
// (compounded), plus round-off. Flat boundaries keep the volume to
// round-off; on a curved discrete boundary, collapses may flatten it within
// their normal-deviation bound, each taking its change from the budget.
double adapted_volume_tolerance(int iterations, double volume_budget);

// Throws InputError ("adapt: ...; nothing written", with the validation
// report or the distance to the model) unless the mesh is valid, and,
// without a model, of `volume` within `relative_tolerance`, or, on a
// model, on it (require_on_model): there the volume moves from the
// input's facets to the model's.
void require_adapted(const Mesh& mesh, const CadModel* model, double volume, double relative_tolerance,
                     const PartRunner& sweeps = {});

}  // namespace metrica
