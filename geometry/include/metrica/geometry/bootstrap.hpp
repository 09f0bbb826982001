// A first mesh of a CAD model (gmsh's Delaunay mesher), with the model's
// surface tags as surface ids and every boundary vertex associated with
// its entity: the start of an adaptation when no mesh exists.
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/mesh_data.hpp>

namespace metrica {

struct BootstrapOptions {
  // Target edge length (0: a tenth of the model's size).
  double size = 0.0;
};

// The mesh as file content, with VerticesOnGeometric* records (the
// parameters gmsh placed each boundary node at). Throws InputError when
// gmsh cannot mesh the model or the model has no volume.
io::MeshData bootstrap_mesh(const CadModel& model, const BootstrapOptions& options = {});

}  // namespace metrica
