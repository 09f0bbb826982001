#include <metrica/error.hpp>
#include <metrica/metrics/analytic_field.hpp>

#include <fmt/core.h>

#include <cmath>
#include <numbers>

namespace metrica {

AnalyticField analytic_field_from_name(std::string_view name) {
  if (name == "sinfun3") return AnalyticField::sinfun3;
  if (name == "tanh3") return AnalyticField::tanh3;
  if (name == "sinatan3") return AnalyticField::sinatan3;
  throw InputError(fmt::format("unknown analytic field '{}' (known: sinfun3, tanh3, sinatan3)", name));
}

const char* to_string(AnalyticField f) {
  switch (f) {
    case AnalyticField::sinfun3: return "sinfun3";
    case AnalyticField::tanh3: return "tanh3";
    case AnalyticField::sinatan3: return "sinatan3";
  }
  return "?";
}

std::vector<std::string> analytic_field_names() { return {"sinfun3", "tanh3", "sinatan3"}; }

double evaluate(AnalyticField f, const Point& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  switch (f) {
    case AnalyticField::sinfun3: {
      const double s = (x - 0.4) * (y - 0.4) * (z - 0.4);
      constexpr double pi = std::numbers::pi;
      const double v = std::sin(50.0 * s);
      if (s <= -pi / 50.0) return 0.1 * v;
      if (s <= 2.0 * pi / 50.0) return v;
      return 0.1 * v;
    }
    case AnalyticField::tanh3: return std::tanh(std::pow(x + 1.3, 20) * std::pow(y - 0.3, 9) * z);
    case AnalyticField::sinatan3:
      return 0.1 * std::sin(50.0 * x * z) + std::atan(0.1 / (std::sin(5.0 * y) - 2.0 * x * z));
  }
  return 0.0;
}

std::vector<double> analytic_field_values(AnalyticField f, const std::vector<Point>& points) {
  std::vector<double> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = evaluate(f, points[i]);
  return out;
}

}  // namespace metrica
