// Analytic metric fields of the UGAWG benchmarks (UGAWG adapt-benchmarks; tests/data/ugawg/README.md):
// M = R diag(h1^-2, h2^-2, h3^-2) R^T with sizes that vary in space.
//
//   linear   h_x = h_y = 0.1, h_z = h0 + 2 (0.1 - h0) |z - 0.5|
//   polar-1  in cylindrical axes (r, t, z): h_r = h0 + 2 (0.1 - h0) |r - 0.5|,
//            h_t = h_z = 0.1
//   polar-2  as polar-1 with h_t = 0.1 d + 0.025 (1 - d), d = min(10 |r - 0.5|, 1)
// with h0 = 0.001.
#pragma once

#include <metrica/ids.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace metrica {

enum class AnalyticMetric { linear, polar1, polar2 };

// "linear", "polar-1", "polar-2"; InputError listing the names otherwise.
AnalyticMetric analytic_metric_from_name(std::string_view name);
const char* to_string(AnalyticMetric m);
std::vector<std::string> analytic_metric_names();

Sym6 evaluate(AnalyticMetric m, const Point& p);

}  // namespace metrica
