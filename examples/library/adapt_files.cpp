// The library from files to files: read a mesh and its metric (libMeshb),
// adapt under chosen policies, check, write the mesh and the metric at its
// vertices, print the UGAWG quality report (docs/library.md walks through
// it).
//   build/examples/library/adapt_files MESH.meshb METRIC.solb OUT.meshb OUT-METRIC.solb
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <exception>
#include <string>

using namespace metrica;

int main(int argc, char** argv) try {
  if (argc != 5) {
    fmt::print(stderr, "usage: adapt_files MESH METRIC OUT-MESH OUT-METRIC\n");
    return 2;
  }
  // 1. The mesh: libMeshb arrays, then the Mesh (adjacency, boundary,
  //    ridges and corners); vertex ids are the file's order, from 0.
  Mesh mesh = build_mesh(io::read_meshb(argv[1]));
  // 2. The metric: one tensor per vertex of the file, in the same order,
  //    checked (count, finite, positive definite), stored at the vertices.
  const std::vector<Sym6> metric = metric_field_from_sol(io::read_sol(argv[2]), mesh.num_vertices(), argv[2]);
  assign_metric(mesh, metric);
  // 3. Adapt: the standard pipeline under the policies named in the
  //    template (compiled once in the library for every listed policy).
  const AdaptReport report = adapt<LogEuclidean, Filtered, Speculative>(mesh, AdaptOptions{});
  const auto& last = report.cycles.back();
  fmt::print("{} cycles and passes, {} vertices, {} tets, {:.1f}% of edges in range, worst mean ratio {:.3f}\n",
             report.cycles.size(), mesh.num_vertices(), mesh.num_tets(), 100 * last.conformity, last.min_quality);
  // 4. Check, then write: the mesh's live entities renumbered densely, and
  //    the metric in that same order (metric_sol).
  if (const auto check = mesh.validate(); !check.ok()) {
    fmt::print(stderr, "{}", check.to_string());
    return 1;
  }
  io::write_meshb(argv[3], extract_mesh_data(mesh));
  io::write_sol(argv[4], metric_sol(mesh));
  fmt::print("{}", format_report(quality_report(mesh)));
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "adapt_files: {}\n", e.what());
  return 1;
}
