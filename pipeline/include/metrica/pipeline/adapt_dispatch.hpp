// Runtime choice of the policies (the CLI's --space, --precision and
// --concurrency) by name, from the policy lists (Spaces, Precisions,
// Concurrencies); the Geometry is ModelOrFacets, on AdaptInputs::model
// when one is given. The pipeline is compiled once per (space,
// concurrency, geometry) triple of the lists, in its own unit
// (adapt_unit.cpp, built once per triple by CMake), so that a build on
// several cores compiles them side by side.
#pragma once

#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/policy_choice.hpp>
#include <metrica/policies/speculative.hpp>

#include <string>
#include <string_view>

namespace metrica {

PointRule point_rule_from_name(std::string_view name);
const char* to_string(PointRule r);

// The standard adaptation with its policies chosen by name (the CLI's
// --space, --precision, --concurrency; inputs.model, when set, the
// model): adapt<S, P, C, ModelOrFacets> for the named policies.
AdaptReport adapt_by_name(Mesh& mesh, const AdaptOptions& options, const PolicyChoice& policies = {},
                          const AdaptInputs& inputs = {});

// adapt<S, precision, C, G>, the precision chosen by name: declared here,
// defined and instantiated for each triple of the lists in adapt_unit.cpp.
template <MetricSpace S, Concurrency C, Geometry G>
AdaptReport adapt_instance(Mesh& mesh, const AdaptOptions& options, const AdaptInputs& inputs,
                           std::string_view precision);

}  // namespace metrica
