// Runtime choice of the policies (the CLI's --space, --precision and
// --concurrency): one explicit instantiation of adapt<> per combination,
// compiled in adapt_<space>[_speculative].cpp so that a build on several
// cores compiles them side by side.
#pragma once

#include <metrica/metrics/quality_report.hpp>
#include <metrica/operators/adapt.hpp>
#include <metrica/policies/speculative.hpp>

#include <string_view>

namespace metrica {

enum class PrecisionKind { fast, filtered, exact };
// "fast", "filtered", "exact"; InputError otherwise.
PrecisionKind precision_from_name(std::string_view name);
const char* to_string(PrecisionKind p);
PointRule point_rule_from_name(std::string_view name);
const char* to_string(PointRule r);

// serial: one thread, reproducible to the bit; speculative: all threads
// (thread_count(), the CLI's --threads).
enum class ConcurrencyKind { serial, speculative };
ConcurrencyKind concurrency_from_name(std::string_view name);
const char* to_string(ConcurrencyKind c);

AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, SpaceKind space, PrecisionKind precision,
                  ConcurrencyKind concurrency = ConcurrencyKind::serial);

// adapt<S, precision, C>: the precision chosen at run time.
template <MetricSpace S, Concurrency C>
AdaptReport adapt_with(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision) {
  switch (precision) {
    case PrecisionKind::fast: return adapt<S, Fast, C>(mesh, options);
    case PrecisionKind::filtered: return adapt<S, Filtered, C>(mesh, options);
    case PrecisionKind::exact: return adapt<S, Exact, C>(mesh, options);
  }
  return {};
}

#define METRICA_ADAPT_INSTANCE(EXTERN, S, C) \
  EXTERN template AdaptReport adapt_with<S, C>(Mesh&, const AdaptOptions&, PrecisionKind);
#define METRICA_ADAPT_INSTANCES(EXTERN)                \
  METRICA_ADAPT_INSTANCE(EXTERN, Isotropic, Serial)    \
  METRICA_ADAPT_INSTANCE(EXTERN, Anisotropic, Serial)  \
  METRICA_ADAPT_INSTANCE(EXTERN, LogEuclidean, Serial) \
  METRICA_ADAPT_INSTANCE(EXTERN, Isotropic, Speculative) \
  METRICA_ADAPT_INSTANCE(EXTERN, Anisotropic, Speculative) \
  METRICA_ADAPT_INSTANCE(EXTERN, LogEuclidean, Speculative)
METRICA_ADAPT_INSTANCES(extern)

}  // namespace metrica
