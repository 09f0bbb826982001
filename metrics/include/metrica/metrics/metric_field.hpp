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

io::SolData metric_field_to_sol(const std::vector<Sym6>& metrics);

std::vector<Sym6> analytic_metric_field(AnalyticMetric m, const std::vector<Point>& points);

// Checks each tensor (finite, SPD); InputError names the first bad one.
void check_metric_field(const std::vector<Sym6>& metrics, const std::string& source);

// Sets M and log M at every live vertex; `metrics` is indexed by vertex id.
void assign_metric(Mesh& mesh, const std::vector<Sym6>& metrics);

}  // namespace metrica
