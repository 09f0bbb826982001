#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/mesh_summary.hpp>

#include <fmt/core.h>

#include <cmath>
#include <filesystem>

namespace metrica::cli {

int run_info(const std::vector<std::string>& args) {
  Options o("info", "[-i] INPUT",
            "Prints what a mesh file holds (keyword counts) and what Metrica derives from it: vertex\n"
            "classes, surface ids with their areas, ridge curves, corners, extent and volume.\n\n"
            "Example: metrica info cube.meshb");
  o.input("mesh (.mesh, .meshb, .msh, .vtu, .su2)");
  if (!o.parse(args)) return kOk;
  const auto input = o.required("input", "the input mesh (-i)");

  auto loaded = load_mesh(input, Valid::not_required);
  if (o.dry_run()) return kOk;
  const auto& d = loaded.data;
  const auto s = summarize(loaded.mesh);
  if (!std::isfinite(s.volume) || !std::isfinite(s.min_tet_volume) || !std::isfinite(s.max_tet_volume))
    throw InputError(fmt::format("{}: the volume is not finite ({})", input, s.volume));
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(input, ec);

  auto row = [](const char* label, const std::string& value) { fmt::print("  {:<20} {}\n", label, value); };
  fmt::print("{}\n", input);
  const io::FileFormat format = io::format_of(input);
  const std::string size_text = ec ? std::string("?") : bytes_text(double(file_size));
  if (format == io::FileFormat::msh)
    row("format", fmt::format("gmsh .msh, {}", size_text));
  else
    row("format",
        fmt::format("libMeshb v{} {}, {}", d.version, format == io::FileFormat::meshb ? "binary" : "ASCII", size_text));
  row("read", fmt::format("{:.3f} s (+ {:.3f} s adjacency)", loaded.read_seconds, loaded.build_seconds));
  fmt::print("File\n");
  row("vertices", count_text(d.vertices.size()));
  row("tetrahedra", count_text(d.tets.size()));
  row("triangles", count_text(d.triangles.size()));
  if (!d.edges.empty()) row("edges", count_text(d.edges.size()));
  if (!d.corners.empty()) row("corners", count_text(d.corners.size()));
  if (!d.ridges.empty()) row("ridges", count_text(d.ridges.size()));
  if (!d.required_vertices.empty()) row("required vertices", count_text(d.required_vertices.size()));
  if (!d.required_edges.empty()) row("required edges", count_text(d.required_edges.size()));
  if (!d.required_triangles.empty()) row("required triangles", count_text(d.required_triangles.size()));
  fmt::print("Mesh\n");
  row("vertices", fmt::format("{} (interior {}, surface {}, ridge {}, corner {})", count_text(s.vertices),
                              count_text(s.interior_vertices), count_text(s.surface_vertices),
                              count_text(s.ridge_vertices), count_text(s.corners)));
  row("tetrahedra", count_text(s.tets));
  row("boundary faces", count_text(s.boundary_faces));
  if (s.internal_faces > 0) row("internal faces", count_text(s.internal_faces));
  row("ridges", fmt::format("{} curves, {} edges", s.ridge_curves, count_text(s.ridge_edges)));
  row("corners", count_text(s.corners));
  row("bounding box", fmt::format("[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]", s.lo.x(), s.hi.x(),
                                  s.lo.y(), s.hi.y(), s.lo.z(), s.hi.z()));
  row("volume", fmt::format("{:.10g}", s.volume));
  row("tet volume", fmt::format("min {:.4g}, max {:.4g}", s.min_tet_volume, s.max_tet_volume));
  fmt::print("Surfaces ({} ids)\n  {:>8} {:>12} {:>14}\n", s.surfaces.size(), "id", "faces", "area");
  for (const auto& [id, surf] : s.surfaces)
    fmt::print("  {:>8} {:>12} {:>14.6g}{}\n", id, count_text(surf.faces), surf.area,
               surf.internal ? "  internal" : "");
  if (s.regions.size() > 1) {
    fmt::print("Regions ({} refs)\n  {:>8} {:>12} {:>14}\n", s.regions.size(), "ref", "tets", "volume");
    for (const auto& [ref, region] : s.regions)
      fmt::print("  {:>8} {:>12} {:>14.6g}\n", ref, count_text(region.tets), region.volume);
  }
  return kOk;
}

}  // namespace metrica::cli
