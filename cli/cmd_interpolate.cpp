#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/point_location.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

namespace metrica::cli {

int run_interpolate(const std::vector<std::string>& args) {
  Options o("interpolate", "[-i] FROM_MESH --field FIELD.solb --to TO_MESH [-o] OUTPUT.solb",
            "Transfers a vertex solution from one mesh to another (a solver restarting on an adapted\n"
            "mesh from its previous solution): each vertex of the target mesh is located in the source\n"
            "mesh by walking from the tet of the previous vertex (around holes, again from a grid of the\n"
            "source's tets), and takes the P1 (barycentric)\n"
            "interpolant there. Target vertices outside the source mesh (a curved boundary discretised\n"
            "differently) take the value at the closest point of the closest tet found; they are counted.\n"
            "Every field of the file moves and the output keeps its fields (e.g. a velocity vector and a\n"
            "pressure scalar): scalars and vectors component by component; symmetric tensors (a metric)\n"
            "log-Euclidean, exp of the interpolant of log M, so that a metric stays positive definite and\n"
            "its sizes are averaged geometrically. Full (non-symmetric) matrices are refused.\n\n"
            "Examples:\n"
            "  metrica interpolate old.meshb --field old.solb --to adapted.meshb -o restart.solb\n"
            "  metrica interpolate solver.meshb --field metric.solb --to start.meshb -o start-metric.solb");
  o.input("source mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  o.output("interpolated field (.sol, .solb)", {io::FileFormat::sol, io::FileFormat::solb});
  o.add()("field", po::value<std::string>()->value_name("FILE"),
          "scalar, vector and symmetric tensor fields at the source's vertices (.sol, .solb)")(
      "to", po::value<std::string>()->value_name("MESH"), "target mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the source mesh (-i)");
  const auto output = o.required("output", "the output field (-o)");
  const auto field_path = o.required("field", "the field (--field)");
  const auto to_path = o.required("to", "the target mesh (--to)");
  Stopwatch clock;
  const auto from = load_mesh(input);
  const auto field = io::read_sol(field_path);
  solution_values_from_sol(field, from.data.vertices.size(), field_path);
  const auto to = load_mesh(to_path);
  if (o.dry_run()) return kOk;
  std::size_t outside = 0;
  const int width = field.stride();
  io::SolData sol = transfer_solution(from.mesh, field, to.mesh, field_path, &outside);
  sol.version = to.data.version;
  sol.count = to.data.vertices.size();
  sol.values.resize(sol.count * static_cast<std::size_t>(width));
  io::write_sol(output, sol, 0, sweep_runner(sol.count));
  if (log::level() >= log::Level::normal)
    fmt::print("wrote {}: {} vertices x {} values ({} outside the source mesh, clamped) in {:.2f} s\n", output,
               count_text(sol.count), width, count_text(outside), clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
