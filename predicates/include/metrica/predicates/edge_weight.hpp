// The max-min Laplacian edge weight criterion (seed, section 3.1; Barth
// 1991), in the inner-product form of Marcum & Alauzet (2013) that needs no
// face normals.
//
// The weight of edge ab of K is the (negated) P1 stiffness entry, -|K|
// grad(phi_a).grad(phi_b): with cd the opposite edge, e = d - c, u = a - c,
// v = b - c,
//     w_ab = ( <e,e><u,v> - <e,u><e,v> ) / (6 |K|)
// (Lagrange's identity turns <e x u, e x v> into inner products). It is
// proportional to |cd| cot(theta_cd), theta_cd the dihedral angle at cd:
// positive for acute dihedrals, negative for obtuse ones. The seed prints
// the bracket with the opposite sign and "max"; its criterion is the same:
// a flip is made when the smallest weight of the new tets is larger than
// the smallest weight of the old ones. In a metric M the inner products
// are <x,y>_M = x^T M y and |K|_M = |K| sqrt(det M), M at K's centroid.
#pragma once

#include <metrica/metrics/measures.hpp>

#include <array>
#include <limits>

namespace metrica {

// Weights of the 6 edges in kEdgeVertex order; all -inf for a tet of
// non-positive volume (never to be preferred).
std::array<double, 6> edge_weights(const TetPoints& k, const Sym6& m);

inline double min_edge_weight(const TetPoints& k, const Sym6& m) {
  double w = std::numeric_limits<double>::infinity();
  for (double x : edge_weights(k, m)) w = std::min(w, x);
  return w;
}

}  // namespace metrica
