// Metric fields: one tensor per vertex, read from a solution file, made
// from an analytic metric, and stored in the Mesh with their logarithms.
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>
#include <metrica/metrics/analytic_metric.hpp>

#include <string>
#include <vector>

namespace metrica {

// The first field of `sol` as metrics: a symmetric tensor as is, a scalar h
// as the isotropic h^-2 I. InputError (naming `source` and the vertex)
// when the count differs from `vertices`, no field fits, or a tensor is
// not finite and symmetric positive definite.
std::vector<Sym6> metric_field_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source);

// The first scalar field of `sol` (a solver variable, say), with the same
// checks: count, finite values.
std::vector<double> scalar_field_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source);
io::SolData scalar_field_to_sol(const std::vector<double>& values);

// Every value of a solution of scalar, vector and symmetric tensor fields,
// vertex-major as stored (SolData::values), checked: count, finite values,
// each symmetric tensor positive definite (a metric). InputError for a
// full (non-symmetric) matrix field.
std::vector<double> solution_values_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source);

// The fields of `sol` (at the vertices of `from`) moved to the vertices of
// `to`, each vertex of `to` located in `from`: scalars and vectors by
// their P1 interpolant, component by component; symmetric tensors
// (metrics) log-Euclidean, exp of the P1 interpolant of log M (an SPD
// tensor, its determinant interpolated geometrically). The checks of
// solution_values_from_sol; `outside` counts the vertices of `to` outside
// `from` (clamped).
io::SolData transfer_solution(const Mesh& from, const io::SolData& sol, const Mesh& to, const std::string& source,
                              std::size_t* outside = nullptr);

// Scalar fields chosen from a solution by a comma-separated selection, for a
// multiscale metric of several variables:
//   K       field K (1-based): a scalar, or every component of a vector;
//   K.x     one component of vector field K (x, y, z or 1, 2, 3);
//   all     every scalar field and every vector component.
// An empty selection is the first scalar field. InputError for a malformed
// selection, a field that does not exist or is a tensor, and the checks of
// scalar_field_from_sol.
// One item of such a selection: `all`, or field K (as written, 1-based)
// and its component (0-2; -1 for the whole field). InputError naming a
// malformed item; whether the fields exist is the solution's to say
// (select_fields).
struct FieldItem {
  bool all = false;
  std::size_t field = 0;
  int component = -1;
};
std::vector<FieldItem> parse_field_selection(const std::string& selection);
struct SelectedField {
  std::string name;  // "2", "1.x": for messages
  std::vector<double> values;
};
std::vector<SelectedField> select_fields(const io::SolData& sol, std::size_t vertices, const std::string& selection,
                                         const std::string& source);

io::SolData metric_field_to_sol(const std::vector<Sym6>& metrics);
// The metric stored at the mesh's live vertices, in the order
// extract_mesh_data() writes them (vertex ids ascending, removed vertices
// skipped): the .sol/.solb that goes with that mesh file.
io::SolData metric_sol(const Mesh& mesh);

std::vector<Sym6> analytic_metric_field(AnalyticMetric m, const std::vector<Point>& points);

// Sizes a metric may ask for (h = 1/sqrt(eigenvalue)): with coordinates
// within +-1e12 (input_checks.hpp), lengths, volumes and the mean ratio
// then stay far from double's overflow and underflow. A size beyond them is
// refused, not clamped; --hmin/--hmax clamp it first when the user asks.
inline constexpr double kSmallestSize = 1e-30;
inline constexpr double kLargestSize = 1e30;

// Checks each tensor: finite, symmetric positive definite; InputError
// names the first bad one.
void check_metric_entries(const std::vector<Sym6>& metrics, const std::string& source);
// check_metric_entries, and every size within [kSmallestSize, kLargestSize].
void check_metric_field(const std::vector<Sym6>& metrics, const std::string& source);

// Sets M and log M at every live vertex; `metrics` is indexed by vertex id.
void assign_metric(Mesh& mesh, const std::vector<Sym6>& metrics);

}  // namespace metrica
