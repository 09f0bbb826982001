// The sizes a curved boundary asks for: facets of a surface with principal
// curvatures k1, k2 turn by about h |k| between neighbouring vertices, so
// a bound `angle` on that turn asks for h <= angle / |k| along each
// principal direction (the chord of an arc of that angle). Flat directions
// ask for nothing. The field's metric is intersected with it at the
// boundary vertices: the facets then follow the model whatever the
// solution asks (the geometric metric of Alauzet & Loseille's adaptive
// loops, here from the CAD model's curvatures).
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/mesh.hpp>

#include <vector>

namespace metrica {

// Per vertex id: the tensor sum over the surfaces around a boundary vertex
// of (k_i / angle)^2 d_i d_i^T for its principal curvatures and directions,
// plus (1 / size)^2 I with `size` the model's size (so that every tensor is
// definite); that isotropic floor alone at interior vertices and on flat
// boundaries. Needs the mesh's boundary associated with the model
// (association.hpp). InputError for an angle outside (0, pi/2].
std::vector<Sym6> curvature_metric(const Mesh& mesh, const CadModel& model, double angle);

}  // namespace metrica
