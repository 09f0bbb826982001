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

}  // namespace metrica
