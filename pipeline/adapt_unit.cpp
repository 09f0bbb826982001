// One (space, concurrency) pair of the policy lists, compiled with
// METRICA_ADAPT_UNIT = its index (space-major): the pipeline under every
// precision for that pair.
#include <metrica/pipeline/adapt_dispatch.hpp>

namespace metrica {

template <MetricSpace S, Concurrency C>
AdaptReport adapt_instance(Mesh& mesh, const AdaptOptions& options, std::string_view precision) {
  return with_policy<Precisions>("precision", precision, [&]<class P>() { return adapt<S, P, C>(mesh, options); });
}

constexpr std::size_t kUnit = METRICA_ADAPT_UNIT;
static_assert(kUnit < Spaces::size * Concurrencies::size,
              "more adapt units than policy pairs (operators/CMakeLists.txt)");
template AdaptReport adapt_instance<Spaces::at<kUnit / Concurrencies::size>,
                                    Concurrencies::at<kUnit % Concurrencies::size>>(Mesh&, const AdaptOptions&,
                                                                                    std::string_view);

}  // namespace metrica
