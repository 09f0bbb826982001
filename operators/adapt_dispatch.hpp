// Runtime choice of the policies (the CLI's --space and --precision): one
// explicit instantiation of adapt<> per combination, compiled in
// adapt_<space>.cpp. The Concurrency policy is Serial until issue 5.
#pragma once

#include <metrica/metrics/quality_report.hpp>
#include <metrica/operators/adapt.hpp>

#include <string_view>

namespace metrica {

enum class PrecisionKind { fast, filtered, exact };
// "fast", "filtered", "exact"; InputError otherwise.
PrecisionKind precision_from_name(std::string_view name);
const char* to_string(PrecisionKind p);
PointRule point_rule_from_name(std::string_view name);
const char* to_string(PointRule r);

AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, SpaceKind space, PrecisionKind precision);

// The instantiations, one per space (adapt_<space>.cpp).
AdaptReport adapt_isotropic(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision);
AdaptReport adapt_anisotropic(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision);
AdaptReport adapt_log_euclidean(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision);

}  // namespace metrica
