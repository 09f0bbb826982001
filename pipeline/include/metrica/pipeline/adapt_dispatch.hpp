// Runtime choice of the policies (the CLI's --space, --precision and
// --concurrency) by name, from the policy lists (Spaces, Precisions,
// Concurrencies). The pipeline is compiled once per (space, concurrency)
// pair, in its own unit (adapt_unit.cpp, built once per pair by CMake),
// so that a build on several cores compiles them side by side.
#pragma once

#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/policies/speculative.hpp>

#include <string>
#include <string_view>

namespace metrica {

PointRule point_rule_from_name(std::string_view name);
const char* to_string(PointRule r);

// The policies of an adaptation, by name (each one of its list's names).
struct PolicyChoice {
  std::string space{Spaces::at<0>::name};
  std::string precision{Precisions::at<0>::name};
  std::string concurrency{Concurrencies::at<0>::name};
};

// InputError naming the choices when a name is not in its list.
void check_policy_choice(const PolicyChoice& choice);

AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, const PolicyChoice& policies = {});

// adapt<S, precision, C>, the precision chosen by name: declared here,
// defined and instantiated for each pair of the lists in adapt_unit.cpp.
template <MetricSpace S, Concurrency C>
AdaptReport adapt_instance(Mesh& mesh, const AdaptOptions& options, std::string_view precision);

}  // namespace metrica
