#include "cli.hpp"

#include <metrica/geometry/association.hpp>
#include <metrica/log.hpp>
#include <metrica/numbering.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

namespace metrica::cli {

int run_check(const std::vector<std::string>& args) {
  Options o("check", "[-i] INPUT",
            "Reads a mesh, builds its adjacency and checks every invariant: positive orientation,\n"
            "symmetric adjacency, surface ids on boundary faces, a closed manifold boundary, up-to-date\n"
            "ridge/corner classification, vertex hints. Exit 0 when valid, 1 with a report when not.\n"
            "With --geometry MODEL it also associates the boundary vertices with the CAD model (the\n"
            "input's VerticesOnGeometric* records, else projection) and reports their largest distance\n"
            "to their entity; exit 1 when a vertex is farther than --model-tolerance.\n\n"
            "Examples:\n"
            "  metrica check cube.meshb\n"
            "  metrica check adapted.meshb --geometry cube-cylinder.step");
  o.input("mesh to check (.mesh, .meshb, .msh, .vtu, .su2)");
  o.add()("max-messages", po::value<int>()->default_value(20)->value_name("N"),
          "problems listed per check (counts stay exact)")("geometry", po::value<std::string>()->value_name("MODEL"),
                                                           "CAD model the boundary must lie on")(
      "model-tolerance", po::value<double>()->default_value(1e-8, "1e-8")->value_name("D"),
      "largest distance of a boundary vertex to its entity (--geometry)");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");
  ValidateOptions vo;
  vo.max_messages_per_check = static_cast<std::size_t>(o.in_range("max-messages", 0, 1000000));
  const double tolerance = o.in_range("model-tolerance", 0.0, 1e300);

  auto loaded = load_mesh(input, Valid::not_required, ridge_angle(o));
  if (o.dry_run()) return kOk;
  const auto report = loaded.mesh.validate(vo);
  if (report.ok() && o.has("geometry")) {
    const auto model = open_geometry(o.get<std::string>("geometry"), loaded.mesh, &loaded.data);
    const ModelDistance d = model_distance(loaded.mesh, *model, tolerance);
    if (log::level() >= log::Level::normal) fmt::print("{}: {}\n", input, model_distance_text(loaded.mesh, *model));
    if (d.max > tolerance) {
      fmt::print("{}: vertex {} is {:.3g} from its entity (tolerance {:.3g})\n", input, numbered(d.worst), d.max,
                 tolerance);
      return kInvalid;
    }
  }
  if (report.ok()) {
    if (log::level() >= log::Level::normal)
      fmt::print("{}: valid ({} vertices, {} tets)\n", input, count_text(loaded.mesh.num_vertices()),
                 count_text(loaded.mesh.num_tets()));
    return kOk;
  }
  fmt::print("{}: {}\n", input, report.to_string());
  return kInvalid;
}

}  // namespace metrica::cli
