#include "cli.hpp"

#include <metrica/log.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

namespace metrica::cli {

int run_check(const std::vector<std::string>& args) {
  Options o("check", "[-i] INPUT",
            "Reads a mesh, builds its adjacency and checks every invariant: positive orientation,\n"
            "symmetric adjacency, surface ids on boundary faces, a closed manifold boundary, up-to-date\n"
            "ridge/corner classification, vertex hints. Exit 0 when valid, 1 with a report when not.\n\n"
            "Example: metrica check cube.meshb");
  o.input("mesh to check (.mesh, .meshb)");
  o.add()("max-messages", po::value<std::size_t>()->default_value(20)->value_name("N"),
      "problems listed per check (counts stay exact)");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");

  auto loaded = load_mesh(input);
  ValidateOptions vo;
  vo.max_messages_per_check = o.get<std::size_t>("max-messages");
  const auto report = loaded.mesh.validate(vo);
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
