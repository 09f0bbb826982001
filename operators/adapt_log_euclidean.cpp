// The LogEuclidean instantiations of the pipeline (one file per space, so that a
// build on several cores compiles them side by side).
#include <metrica/operators/adapt_dispatch.hpp>

namespace metrica {

AdaptReport adapt_log_euclidean(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision) {
  switch (precision) {
    case PrecisionKind::fast: return adapt<LogEuclidean, Fast, Serial>(mesh, options);
    case PrecisionKind::filtered: return adapt<LogEuclidean, Filtered, Serial>(mesh, options);
    case PrecisionKind::exact: return adapt<LogEuclidean, Exact, Serial>(mesh, options);
  }
  return {};
}

}  // namespace metrica
