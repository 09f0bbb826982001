#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/log.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

namespace metrica::cli {

std::unique_ptr<CadModel> open_geometry(const std::string& path, Mesh& mesh, const io::MeshData* input, bool adapting) {
  Stopwatch clock;
  auto model = std::make_unique<CadModel>(path);
  const AssociationReport r = associate(mesh, *model, input);
  log::info("{}: {} surfaces, {} curves, {} model vertices ({:.2f} s)", path, model->entities(2).size(),
            model->entities(1).size(), model->entities(0).size(), clock.seconds());
  if (log::level() < log::Level::normal) return model;
  // What the input is on the model, before any work.
  fmt::print(
      "{}: {} boundary vertices associated ({} with the input's parameters), the farthest {:.3g} from the "
      "model\n",
      path, count_text(r.vertices), count_text(r.from_file), r.max_distance);
  if (r.records_refused > 0)
    fmt::print(
        "{}: the input's parameters of {} vertices name points up to {:.3g} away from them (another kernel's "
        "parameterization?): those vertices were projected onto the model instead\n",
        path, count_text(r.records_refused), r.refused_distance);
  if (r.off_model > 0)
    fmt::print("{}: {} boundary vertices farther than {:.0e} from the model{}\n", path, count_text(r.off_model),
               kOnModel, adapting ? "; the first stage brings them onto it" : "");
  std::fflush(stdout);
  return model;
}

std::string model_distance_text(const Mesh& mesh, const CadModel& model) {
  const ModelDistance d = model_distance(mesh, model);
  std::string text = fmt::format("boundary vertices on {}: {}, largest distance to their entity {:.3g}", model.source(),
                                 count_text(d.vertices), d.max);
  if (d.beyond > 0) text += fmt::format(" ({} beyond 1e-8)", count_text(d.beyond));
  if (d.unassociated > 0) text += fmt::format(", {} without an entity", count_text(d.unassociated));
  return text;
}

}  // namespace metrica::cli
