// Analytic scalar fields of the verification study (seed, section 5.2,
// eqs. (sinfun3), (tanh3), (sinatan3); Galbraith et al. 2020), on the unit
// cube:
//   sinfun3   s = (x-0.4)(y-0.4)(z-0.4);  sin(50 s) where -pi/50 < s <= 2pi/50,
//             0.1 sin(50 s) elsewhere (a shell of strong oscillation)
//   tanh3     tanh((x+1.3)^20 (y-0.3)^9 z)
//   sinatan3  0.1 sin(50 x z) + atan(0.1 / (sin(5 y) - 2 x z))
// They stand in for a flow solution: a multiscale metric is made from
// their values at the vertices, and the P1 interpolation error is measured.
#pragma once

#include <metrica/ids.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace metrica {

enum class AnalyticField { sinfun3, tanh3, sinatan3 };

// InputError listing the known names otherwise.
AnalyticField analytic_field_from_name(std::string_view name);
const char* to_string(AnalyticField f);
std::vector<std::string> analytic_field_names();

double evaluate(AnalyticField f, const Point& p);
std::vector<double> analytic_field_values(AnalyticField f, const std::vector<Point>& points);

}  // namespace metrica
