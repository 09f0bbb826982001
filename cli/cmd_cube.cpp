#include "cli.hpp"

#include <metrica/box.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/log.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace metrica::cli {

int run_cube(const std::vector<std::string>& args) {
  Options o("cube", "--n N [NY NZ] -o OUTPUT",
            "Writes the box [lo, hi] split into N x NY x NZ hexes of 6 tets each (Kuhn subdivision), with\n"
            "surface ids 1..6 on x = lo, x = hi, y = lo, y = hi, z = lo, z = hi. --n 3 gives the UGAWG\n"
            "start mesh (4 x 4 x 4 vertices, 162 tets).\n\n"
            "Example: metrica cube --n 3 -o cube.meshb");
  o.add()("n", po::value<std::vector<int>>()->multitoken()->value_name("N [NY NZ]"),
          "hexes per direction (one value for all three, or three)")(
      "lo", po::value<std::string>()->value_name("X,Y,Z"), "lower corner (default 0,0,0; negative: --lo=-1,-1,-1)")(
      "hi", po::value<std::string>()->value_name("X,Y,Z"), "upper corner (default 1,1,1)");
  o.output(
      "output mesh (.mesh, .meshb, .msh, .vtu, .su2)",
      {io::FileFormat::mesh, io::FileFormat::meshb, io::FileFormat::msh, io::FileFormat::vtu, io::FileFormat::su2});
  o.format_version("libMeshb version to write, 1-4 (default 2)");
  if (!o.parse(args)) return kOk;

  BoxSpec spec;
  if (!o.has("n")) throw UsageError("cube: missing --n");
  const auto n = o.get<std::vector<int>>("n");
  if (n.size() == 1)
    spec.nx = spec.ny = spec.nz = n[0];
  else if (n.size() == 3)
    spec.nx = n[0], spec.ny = n[1], spec.nz = n[2];
  else
    throw UsageError("cube: --n takes one value or three");
  auto corner = [&](const char* name, Point& p) {
    if (!o.has(name)) return;
    const auto text = o.get<std::string>(name);
    double x, y, z;
    char tail;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &tail) != 3)
      throw UsageError(fmt::format("cube: --{} takes X,Y,Z, got '{}'", name, text));
    p = Point(x, y, z);
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) <= kCoordinateLimit))
        throw UsageError(fmt::format("cube: --{} coordinates must be finite and within +-{:g}, got '{}'", name,
                                     kCoordinateLimit, text));
  };
  corner("lo", spec.lo);
  corner("hi", spec.hi);
  o.as_usage([&] { check_box_spec(spec); });
  const auto output = o.required("output", "the output file (-o)");
  const int version = o.format_version();
  if (o.dry_run()) return kOk;

  Stopwatch clock;
  auto data = box_mesh_data(spec);
  data.version = version != 0 ? version : 2;
  io::write_mesh_file(output, data);
  if (log::level() >= log::Level::normal)
    fmt::print("wrote {}: {} vertices, {} tets, {} boundary triangles ({:.2f} s)\n", output,
               count_text(data.vertices.size()), count_text(data.tets.size()), count_text(data.triangles.size()),
               clock.seconds());
  return kOk;
}

}  // namespace metrica::cli
