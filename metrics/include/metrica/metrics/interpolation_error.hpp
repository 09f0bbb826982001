// The L2 norm of the P1 interpolation error of a field: the error of the
// piecewise-linear interpolant u_h (the values at the vertices) against a
// reference u, integrated tet by tet with the degree-5 Grundmann-Moeller
// rule (quadrature.hpp):
//   || u - u_h ||_L2 = sqrt( sum_T |T| sum_q w_q (u(x_q) - u_h(x_q))^2 ).
// The verification study of the seed (section 5.2) and of the UGAWG
// error-estimation results measures this with u analytic.
#pragma once

#include <metrica/mesh.hpp>

#include <functional>
#include <vector>

namespace metrica {

using ScalarFunction = std::function<double(const Point&)>;

// u at every live vertex, indexed by vertex id (0 at dead ids): the P1
// interpolant's values.
std::vector<double> values_at_vertices(const Mesh& mesh, const ScalarFunction& u);

// `values` indexed by vertex id (dead entries ignored). InputError when
// the sizes do not match or a value is not finite.
double l2_interpolation_error(const Mesh& mesh, const std::vector<double>& values, const ScalarFunction& exact);

// The same with u evaluated at many quadrature points per call (the points
// of a few thousand tets in, their values out): for a u that is cheap only
// in bulk, as a vectorized Python function is. InputError when it
// returns another count of values or a value that is not finite.
using PointsFunction = std::function<std::vector<double>(const std::vector<Point>&)>;
double l2_interpolation_error_in_bulk(const Mesh& mesh, const std::vector<double>& values, const PointsFunction& exact);

// The L2 norm of u_h - v_h for two P1 fields on the same mesh (the error
// against the finest mesh's solution, once transferred).
double l2_difference(const Mesh& mesh, const std::vector<double>& a, const std::vector<double>& b);

}  // namespace metrica
