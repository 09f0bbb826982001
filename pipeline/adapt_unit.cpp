// One (space, concurrency, geometry) triple of the policy lists, compiled
// with METRICA_ADAPT_UNIT = its index (space-major, geometry last): the
// standard stages of that triple, and the pipeline under every precision
// of its metric-Delaunay criterion.
#include <metrica/error.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <type_traits>

namespace metrica {

template <MetricSpace S, Concurrency C, Geometry G>
AdaptReport adapt_instance(Mesh& mesh, const AdaptOptions& options, const AdaptInputs& inputs,
                           std::string_view precision) {
  const G geometry = geometry_of<G>(inputs);
  return with_policy<Precisions>("precision", precision, [&]<class P>() -> AdaptReport {
    if constexpr (METRICA_DEFAULT_POLICIES_ONLY && !std::is_same_v<P, Precisions::at<0>>)
      throw InputError(not_compiled_message("precision", P::name, Precisions::at<0>::name));
    else
      return adapt<S, P, C, G>(mesh, options, inputs, geometry);
  });
}

// Unit k is the k-th compiled triple (compiled_policies.hpp's order).
constexpr std::size_t kUnit = METRICA_ADAPT_UNIT;
constexpr std::size_t kPerSpace = METRICA_COMPILED_CONCURRENCIES * Geometries::size;
static_assert(kUnit < METRICA_ADAPT_UNITS, "more adapt units than compiled triples (pipeline/CMakeLists.txt)");
using UnitSpace = Spaces::at<kUnit / kPerSpace>;
using UnitConcurrency = Concurrencies::at<kUnit % kPerSpace / Geometries::size>;
using UnitGeometry = Geometries::at<kUnit % Geometries::size>;

// The standard stages of the triple (declared in adapt.hpp).
static_assert(!METRICA_DEFAULT_POLICIES_ONLY || kUnit < kPerSpace, "the default space's units only");
static_assert(!METRICA_SPECULATIVE_ONLY || kUnit < Geometries::size, "the default concurrency's units only");
METRICA_STANDARD_STAGES_OF_TRIPLE(, UnitSpace, UnitConcurrency, UnitGeometry)

template AdaptReport adapt_instance<UnitSpace, UnitConcurrency, UnitGeometry>(Mesh&, const AdaptOptions&,
                                                                              const AdaptInputs&, std::string_view);

}  // namespace metrica
