#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/geometry/bootstrap.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/timer.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica::cli {

int run_bootstrap(const std::vector<std::string>& args) {
  Options o("bootstrap", "[-i] MODEL [-o] OUTPUT [--size H]",
            "Writes a first, coarse tetrahedral mesh of a CAD model (any file gmsh opens: .step .stp\n"
            ".iges .igs .brep .geo), meshed by gmsh with edges of about --size, the model's surface tags\n"
            "as surface ids and every boundary vertex associated with its model vertex, curve or surface\n"
            "(VerticesOnGeometric* records in .mesh/.meshb): the start of `adapt --geometry MODEL`.\n"
            "The mesh is checked with validate() and its boundary with the model before it is written.\n\n"
            "Example:\n"
            "  metrica bootstrap cube-cylinder.step -o start.meshb --size 0.2\n"
            "  metrica adapt start.meshb --geometry cube-cylinder.step --analytic polar-2 -o cc.meshb");
  o.input("CAD model (.step .stp .iges .igs .brep .geo)");
  o.output(
      "mesh (.mesh, .meshb; .vtu, .su2 without the association)",
      {io::FileFormat::mesh, io::FileFormat::meshb, io::FileFormat::msh, io::FileFormat::vtu, io::FileFormat::su2});
  o.add()("size", po::value<double>()->value_name("H"),
          "target edge length (default: a tenth of the model's diagonal)");
  o.format_version("libMeshb version to write, 1-4 (default 2)");
  o.msh_binary();
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the CAD model (-i)");
  const auto output = o.required("output", "the output mesh (-o)");
  BootstrapOptions bo;
  if (o.has("size")) bo.size = o.positive("size");
  const int version = o.format_version();
  Stopwatch clock;
  CadModel model(input);
  if (bo.size > 0.0 && bo.size < 1e-4 * model.size())
    throw UsageError(fmt::format("bootstrap: --size {} is below 1e-4 of the model's size {:.3g} (too many tets)",
                                 bo.size, model.size()));
  if (o.dry_run()) return kOk;
  auto data = bootstrap_mesh(model, bo);
  Mesh mesh = build_mesh(data, {.source = input});
  const auto check = mesh.validate();
  if (!check.ok())
    throw InputError(fmt::format("bootstrap: gmsh's mesh is invalid; nothing written\n{}", check.to_string()));
  // The association as the adaptation will read it back.
  associate(mesh, model, &data);
  auto out = extract_mesh_data(mesh);
  out.version = version != 0 ? version : 2;
  complete_geometry_records(out, model);
  io::write_mesh_file(output, out, 0, {}, io::FileFormat::mesh, o.msh_encoding());
  if (log::level() >= log::Level::normal) {
    fmt::print("wrote {}: {} vertices, {} tets, {} boundary triangles ({:.2f} s)\n", output,
               count_text(out.vertices.size()), count_text(out.tets.size()), count_text(out.triangles.size()),
               clock.seconds());
    fmt::print("{}\n", model_distance_text(mesh, model));
  }
  return kOk;
}

}  // namespace metrica::cli
