// Gradient and Hessian recovery of a P1 field by L2 projection: the
// gradient at a vertex is the volume-weighted mean of the (constant) P1
// gradients of its tets; the Hessian is the same projection applied to the
// recovered gradient, symmetrised. This is the recovery behind the
// multiscale metrics of refine that the seed uses (section 5.2). On a
// mesh whose vertex stars are centrally symmetric (the Kuhn box), it is
// exact for quadratic fields at vertices whose whole star is interior.
#pragma once

#include <metrica/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace metrica {

// `values` and the results are indexed by vertex id; InputError when the
// sizes differ or a value is not finite.
std::vector<Eigen::Vector3d> recover_gradient(const Mesh& mesh, const std::vector<double>& values);
std::vector<Sym6> recover_hessian(const Mesh& mesh, const std::vector<double>& values);
std::vector<Sym6> recover_hessian(const Mesh& mesh, const std::vector<Eigen::Vector3d>& gradient);

// Replaces the Hessian at boundary vertices (any class but interior) by the
// mean of their interior neighbours' Hessians, in passes (a boundary vertex
// with no interior neighbour waits until a neighbour has been filled), as
// refine's multiscale metric does (ref_metric_extrapolate_boundary_multipass).
// Why: the projected gradient at a boundary vertex is one-sided, first-order
// accurate, so projecting it again gives a second derivative with an O(1)
// error there; the error grows as the mesh is refined and asks for sizes
// that pile vertices onto the boundary. Returns the number of passes.
int extrapolate_hessian_to_boundary(const Mesh& mesh, std::vector<Sym6>& hessian);

}  // namespace metrica
