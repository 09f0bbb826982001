// Intersection of two metrics by simultaneous reduction (Alauzet & Frey,
// INRIA RR-4759, 2003): in the basis P where both are diagonal
// (P^T A P = I, P^T B P = diag(mu)), keep the larger eigenvalue in each
// direction. The result's unit ball is the largest ellipsoid inside both
// unit balls' intersection along the common axes: it asks for the smaller
// size of the two in every direction.
#pragma once

#include <metrica/metrics/sym_tensor.hpp>

namespace metrica {

Sym6 intersect(const Sym6& a, const Sym6& b);

}  // namespace metrica
