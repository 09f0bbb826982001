// Vertex fields between numpy and Metrica: arrays hold one row per live
// vertex in the file order (vertex ids ascending), the library's fields are
// indexed by vertex id. And the functions on fields: analytic fields and
// metrics, the multiscale metric, intersection, complexity, interpolation
// to another mesh, the L2 error.
#pragma once

#include "mesh_arrays.hpp"

#include <metrica/ids.hpp>
#include <metrica/metrics/metric_bounds.hpp>

#include <string>
#include <vector>

namespace metrica::python {

// An (n,) array (width 0) or (n, width) float64 array as values by vertex
// id, `width` per vertex (1 for width 0); InputError naming `what` for
// another shape, dtype or row count, or a value that is not finite.
std::vector<double> values_by_id(const Mesh& mesh, const py::object& values, std::size_t width, const char* what);
// And back: (n,) for width 0, else (n, width).
py::array_t<double> values_array(const Mesh& mesh, const std::vector<double>& by_id, std::size_t width);

// Metrics: (n, 6) in libMeshb order (xx, xy, yy, xz, yz, zz), checked
// symmetric positive definite when `check` (else by the caller, after
// clamping the sizes, as the command does).
std::vector<Sym6> metric_by_id(const Mesh& mesh, const py::object& metric, const char* what = "metric",
                               bool check = true);
py::array_t<double> metric_array(const Mesh& mesh, const std::vector<Sym6>& by_id);

// Size bounds [hmin, hmax] (None: none), checked.
MetricBounds bounds_of(const py::object& hmin, const py::object& hmax);
// The points by vertex id (zero at dead ids).
std::vector<Point> vertex_points(const Mesh& mesh);

py::array_t<double> analytic_metric(const PyMesh& m, const std::string& name, const py::object& hmin,
                                    const py::object& hmax);
py::array_t<double> analytic_field(const PyMesh& m, const std::string& name);

// `metrica metric --field`: the multiscale metric of one field ((n,)) or of
// several intersected ((n, k)), scaled to `complexity`, bounded and graded.
py::array_t<double> multiscale_metric(const PyMesh& m, const py::object& field, double complexity, double norm,
                                      const py::object& gradation, const py::object& hmin, const py::object& hmax,
                                      const py::object& max_anisotropy);
// The recovered Hessian of a field (n,) (recovery.hpp), (n, 6); and the
// multiscale metric of a Hessian the user gives (n, 6), as for a field.
py::array_t<double> hessian(const PyMesh& m, const py::object& field);
py::array_t<double> hessian_metric(const PyMesh& m, const py::object& hessian, double complexity, double norm,
                                   const py::object& gradation, const py::object& hmin, const py::object& hmax,
                                   const py::object& max_anisotropy);
py::array_t<double> intersect(const py::object& a, const py::object& b);
double complexity(const PyMesh& m, const py::object& metric);

// The P1 interpolant of `field` ((n,) or (n, k) on `from`) at the vertices
// of `to`.
py::array_t<double> interpolate(const PyMesh& from, const py::object& field, const PyMesh& to, bool metric);

// The L2 error of the P1 field `values` against the analytic field
// `exact`, or (with `reference`) against the reference mesh's field
// `reference_values`, the field carried to the reference mesh first.
double l2_error(const PyMesh& m, const py::object& values, const py::object& exact, const py::object& reference,
                const py::object& reference_values);

}  // namespace metrica::python
