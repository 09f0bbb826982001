// The Anisotropic instantiations of the pipeline (one file per space, so that a
// build on several cores compiles them side by side).
#include <metrica/operators/adapt_dispatch.hpp>

namespace metrica {

AdaptReport adapt_anisotropic(Mesh& mesh, const AdaptOptions& options, PrecisionKind precision) {
  switch (precision) {
    case PrecisionKind::fast: return adapt<Anisotropic, Fast, Serial>(mesh, options);
    case PrecisionKind::filtered: return adapt<Anisotropic, Filtered, Serial>(mesh, options);
    case PrecisionKind::exact: return adapt<Anisotropic, Exact, Serial>(mesh, options);
  }
  return {};
}

}  // namespace metrica
