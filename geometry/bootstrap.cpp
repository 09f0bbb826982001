#include "gmsh_library.hpp"
#include "keep_threads.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/bootstrap.hpp>

#include <fmt/core.h>

#include <cmath>
#include <unordered_map>

namespace metrica {

io::MeshData bootstrap_mesh(const CadModel& model, const BootstrapOptions& options) {
  if (model.entities(3).empty()) throw InputError(fmt::format("{}: the model has no volume to mesh", model.source()));
  const double h = options.size > 0.0 ? options.size : 0.1 * model.size();
  if (!std::isfinite(h)) throw InputError("bootstrap: the target size must be finite");
  io::MeshData d;
  const detail::KeepThreads keep;
  try {
    gmsh_api::model::mesh::clear();
    gmsh_api::option::setNumber("Mesh.MeshSizeMax", h);
    gmsh_api::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh_api::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh_api::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    // On several threads gmsh's result varies in its last bits from run
    // to run; one thread gives the same mesh every time.
    gmsh_api::option::setNumber("General.NumThreads", 1);
    gmsh_api::model::mesh::generate(3);

    std::unordered_map<std::size_t, VertexId> index;
    // Nodes entity by entity (without their boundary: each node once),
    // with the parameters gmsh placed them at.
    for (int dim = 0; dim <= 3; ++dim)
      for (int tag : model.entities(dim)) {
        std::vector<std::size_t> nodes;
        std::vector<double> coord, param;
        gmsh_api::model::mesh::getNodes(nodes, coord, param, dim, tag, false, true);
        const bool has_param = dim >= 1 && dim <= 2 && param.size() == nodes.size() * std::size_t(dim);
        for (std::size_t i = 0; i < nodes.size(); ++i) {
          const auto v = static_cast<VertexId>(d.vertices.size());
          index[nodes[i]] = v;
          d.vertices.emplace_back(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]);
          d.vertex_refs.push_back(0);
          if (dim == 0) d.on_geometry[0].push_back({v, tag, 0.0, 0.0, 0.0});
          if (dim == 1 && has_param) d.on_geometry[1].push_back({v, tag, param[i], 0.0, 0.0});
          if (dim == 2 && has_param) d.on_geometry[2].push_back({v, tag, param[2 * i], param[2 * i + 1], 0.0});
        }
      }
    auto id = [&](std::size_t node) {
      const auto it = index.find(node);
      if (it == index.end()) throw InputError(fmt::format("bootstrap: gmsh element refers to unknown node {}", node));
      return it->second;
    };
    for (int tag : model.entities(2)) {
      std::vector<std::size_t> tris;
      std::vector<std::size_t> elements;
      gmsh_api::model::mesh::getElementsByType(2, elements, tris, tag);
      for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
        d.triangles.push_back({id(tris[i]), id(tris[i + 1]), id(tris[i + 2])});
        d.triangle_refs.push_back(tag);
      }
    }
    for (int tag : model.entities(3)) {
      std::vector<std::size_t> tets;
      std::vector<std::size_t> elements;
      gmsh_api::model::mesh::getElementsByType(4, elements, tets, tag);
      for (std::size_t i = 0; i + 3 < tets.size(); i += 4) {
        d.tets.push_back({id(tets[i]), id(tets[i + 1]), id(tets[i + 2]), id(tets[i + 3])});
        d.tet_refs.push_back(tag);
      }
    }
    gmsh_api::model::mesh::clear();
  } catch (const gmsh_api::GmshError& e) {
    throw InputError(fmt::format("gmsh could not mesh {}: {}", model.source(), e.what()));
  }
  if (d.tets.empty()) throw InputError(fmt::format("gmsh made no tetrahedron for {}", model.source()));
  return d;
}

}  // namespace metrica
