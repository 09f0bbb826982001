// The Isotropic x Serial instantiations of the pipeline (adapt_dispatch.hpp).
#include <metrica/operators/adapt_dispatch.hpp>

namespace metrica {

template AdaptReport adapt_with<Isotropic, Serial>(Mesh&, const AdaptOptions&, PrecisionKind);

}  // namespace metrica
