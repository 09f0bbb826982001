// Size gradation (Alauzet, "Size gradation control of anisotropic meshes",
// Finite Elem. Anal. Des. 46, 2010): bounds how fast sizes may grow along
// an edge, so that a mesh can follow the metric without bad elements.
// The metric of a vertex p, grown along the edge pq, limits the metric of
// q: M_q <- M_q ∩ grow(M_p, pq), for every edge in both directions.
//
//   metric space (sec. 6.1):  grow(M, e) = (1 + l_M(e) ln b)^-2 M;
//   mixed space (sec. 6.2.1): each eigenvalue l_i of M is multiplied by
//     [(1 + sqrt(l_i) |e| ln b)^t (1 + l_M(e) ln b)^(1-t)]^-2, t = 1/8:
//     mostly the metric-space growth, with a share of the physical one.
// b >= 1 is the gradation (sizes may grow by at most a factor b per unit
// metric length). Passes run in Gauss-Seidel order until no tensor changes
// by more than `tolerance` (relative) or `max_passes` is reached.
#pragma once

#include <metrica/mesh.hpp>

#include <string_view>
#include <vector>

namespace metrica {

enum class GradationSpace { metric, mixed };
GradationSpace gradation_space_from_name(std::string_view name);

struct GradationOptions {
  double beta = 3.0;
  GradationSpace space = GradationSpace::mixed;
  double t = 1.0 / 8.0;
  int max_passes = 10;
  double tolerance = 1e-3;
};

struct GradationStats {
  int passes = 0;
  std::size_t changed_last_pass = 0;
};

// InputError when beta < 1 or the field does not match the mesh.
GradationStats limit_gradation(const Mesh& mesh, std::vector<Sym6>& field, const GradationOptions& options);

}  // namespace metrica
