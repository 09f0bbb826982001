#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/timer.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

namespace metrica::cli {

int run_convert(const std::vector<std::string>& args) {
  Options o("convert", "[-i] INPUT [-o] OUTPUT",
            "Converts a mesh between .mesh / .meshb (any libMeshb version), .msh, .vtu and .su2, or a\n"
            "solution between .sol and .solb. Every keyword Metrica knows is carried over unchanged. A mesh is\n"
            "checked first (as `metrica check`) unless --no-check; an invalid one is not written.\n\n"
            "Examples: metrica convert cube.mesh cube.meshb\n"
            "          metrica convert cube.meshb cube.vtu\n"
            "          metrica convert metric.solb metric.sol --format-version 2");
  o.input("input file");
  o.output("output file; its extension picks the format",
           {io::FileFormat::mesh, io::FileFormat::meshb, io::FileFormat::msh, io::FileFormat::vtu, io::FileFormat::su2,
            io::FileFormat::sol, io::FileFormat::solb});
  o.format_version("libMeshb version to write (default: the input's)");
  o.msh_binary();
  o.add()("no-check", "write even if the mesh fails its checks");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input file (-i)");
  const auto output = o.required("output", "the output file (-o)");
  const int version = o.format_version();

  Stopwatch clock;
  const auto in_format = io::format_of(input), out_format = io::format_of(output);
  const bool in_sol = in_format == io::FileFormat::sol || in_format == io::FileFormat::solb;
  const bool out_sol = out_format == io::FileFormat::sol || out_format == io::FileFormat::solb;
  if (in_sol != out_sol)
    throw UsageError(
        fmt::format("convert: cannot convert {} to {} (a solution converts to a solution, a mesh to a mesh)",
                    io::to_string(in_format), io::to_string(out_format)));
  if (in_format == io::FileFormat::unknown)
    throw UsageError(
        fmt::format("convert: cannot read {} (Metrica reads .mesh, .meshb, .msh, .vtu, .su2, .sol and .solb)", input));
  if (in_sol) {
    const auto sol = io::read_sol(input);
    if (o.dry_run()) return kOk;
    io::write_sol(output, sol, version, sweep_runner(sol.count));
    if (log::level() >= log::Level::normal)
      fmt::print("wrote {}: {} vertices x {} fields ({:.2f} s)\n", output, count_text(sol.count), sol.types.size(),
                 clock.seconds());
    return kOk;
  }

  const auto data = io::read_mesh_file(input);
  check_coordinates(data, input);
  if (o.dry_run()) return kOk;
  if (!o.has("no-check")) {
    BuildOptions bo;
    bo.source = input;
    ValidateOptions vo;
    vo.run = sweep_runner(data.tets.size());
    const auto report = build_mesh(data, bo).validate(vo);
    if (!report.ok()) {
      fmt::print(stderr, "{}: {}\n", input, report.to_string());
      throw InputError(fmt::format("{}: invalid mesh, not converted (use --no-check to convert anyway)", input));
    }
  }
  io::write_mesh_file(output, data, version, sweep_runner(data.tets.size()), io::FileFormat::mesh, o.msh_encoding());
  if (log::level() >= log::Level::normal)
    fmt::print("wrote {}: {} vertices, {} tets, {} triangles ({:.2f} s)\n", output, count_text(data.vertices.size()),
               count_text(data.tets.size()), count_text(data.triangles.size()), clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
