#include <metrica/error.hpp>
#include <metrica/operators/adapt_dispatch.hpp>

#include <fmt/core.h>

namespace metrica {

PointRule point_rule_from_name(std::string_view name) {
  if (name == "edge") return PointRule::edge;
  if (name == "centroid") return PointRule::centroid;
  throw InputError(fmt::format("unknown point creation rule '{}' (edge, centroid)", name));
}

const char* to_string(PointRule r) { return r == PointRule::edge ? "edge" : "centroid"; }

PrecisionKind precision_from_name(std::string_view name) {
  if (name == "fast") return PrecisionKind::fast;
  if (name == "filtered") return PrecisionKind::filtered;
  if (name == "exact") return PrecisionKind::exact;
  throw InputError(fmt::format("unknown precision '{}' (fast, filtered, exact)", name));
}

const char* to_string(PrecisionKind p) {
  switch (p) {
    case PrecisionKind::fast: return "fast";
    case PrecisionKind::filtered: return "filtered";
    case PrecisionKind::exact: return "exact";
  }
  return "?";
}

ConcurrencyKind concurrency_from_name(std::string_view name) {
  if (name == "serial") return ConcurrencyKind::serial;
  if (name == "speculative") return ConcurrencyKind::speculative;
  throw InputError(fmt::format("unknown concurrency '{}' (serial, speculative)", name));
}

const char* to_string(ConcurrencyKind c) { return c == ConcurrencyKind::serial ? "serial" : "speculative"; }

AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, SpaceKind space, PrecisionKind precision,
                  ConcurrencyKind concurrency) {
  const bool serial = concurrency == ConcurrencyKind::serial;
  switch (space) {
    case SpaceKind::isotropic:
      return serial ? adapt_with<Isotropic, Serial>(mesh, options, precision)
                    : adapt_with<Isotropic, Speculative>(mesh, options, precision);
    case SpaceKind::anisotropic:
      return serial ? adapt_with<Anisotropic, Serial>(mesh, options, precision)
                    : adapt_with<Anisotropic, Speculative>(mesh, options, precision);
    case SpaceKind::log_euclidean:
      return serial ? adapt_with<LogEuclidean, Serial>(mesh, options, precision)
                    : adapt_with<LogEuclidean, Speculative>(mesh, options, precision);
  }
  throw InputError("unknown space");
}

}  // namespace metrica
