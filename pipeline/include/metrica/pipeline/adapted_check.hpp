// What an adapted mesh must be before it is written or handed back: valid,
// of the input's volume within what the adaptations may change (without a
// model) and on the model (with one). The command, the loop and the Python
// module share these checks, and what follows when threads fail them.
#pragma once

#include <metrica/error.hpp>
#include <metrica/geometry/cad_model.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>
#include <metrica/pipeline/policy_choice.hpp>

#include <string>
#include <string_view>
#include <utility>

namespace metrica {

// An adapted mesh that fails require_adapted: an InputError of its own
// type, so that a caller tells a failed end check from any other refusal.
class NotAdapted : public InputError {
 public:
  using InputError::InputError;
};

// The relative change of volume `iterations` adaptations may make, each
// within its AdaptOptions::volume_budget of the volume it starts from
// (compounded), plus round-off. Flat boundaries keep the volume to
// round-off; on a curved discrete boundary, collapses may flatten it within
// their normal-deviation bound, each taking its change from the budget.
double adapted_volume_tolerance(int iterations, double volume_budget);

// Throws NotAdapted ("adapt: ...; nothing written", with the validation
// report or the distance to the model) unless the mesh is valid, and,
// without a model, of `volume` within `relative_tolerance`, or, on a
// model, on it (require_on_model): there the volume moves from the
// input's facets to the model's.
void require_adapted(const Mesh& mesh, const CadModel* model, double volume, double relative_tolerance,
                     const PartRunner& sweeps = {});

// attempt(policies): one adaptation of the input, up to require_adapted.
// When a run on threads fails that check (their order of operations left,
// say, a vertex off the model), a warning and the same again from the
// input under the serial concurrency, whose order writes the same mesh on
// every run; a serial run's failure is the caller's error. `again` says
// where from and how, in the caller's words ("from in.meshb under
// --concurrency serial").
template <class Attempt>
auto adapt_or_again_serially(PolicyChoice policies, std::string_view again, Attempt&& attempt) {
  try {
    return attempt(std::as_const(policies));
  } catch (const NotAdapted& e) {
    if (policies.concurrency == Serial::name) throw;
    std::string what = e.what();
    if (const auto at = what.find("; nothing written"); at != std::string::npos) what.erase(at, 17);
    log::warn(
        "{}\nadapting again {} (the threads' order of operations left this; the serial order writes the same mesh "
        "on every run)",
        what, again);
  }
  policies.concurrency = std::string(Serial::name);
  return attempt(std::as_const(policies));
}

}  // namespace metrica
