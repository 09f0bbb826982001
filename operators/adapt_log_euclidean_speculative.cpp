// The LogEuclidean x Speculative instantiations of the pipeline (adapt_dispatch.hpp).
#include <metrica/operators/adapt_dispatch.hpp>

namespace metrica {

template AdaptReport adapt_with<LogEuclidean, Speculative>(Mesh&, const AdaptOptions&, PrecisionKind);

}  // namespace metrica
