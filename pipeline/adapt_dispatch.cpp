#include <metrica/error.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <fmt/core.h>

#include <type_traits>

namespace metrica {

static_assert(Spaces::size * Concurrencies::size * Geometries::size == METRICA_ADAPT_UNITS,
              "one adapt unit per (space, concurrency, geometry) triple: update METRICA_ADAPT_UNITS in "
              "pipeline/CMakeLists.txt");

PointRule point_rule_from_name(std::string_view name) {
  if (name == "edge") return PointRule::edge;
  if (name == "centroid") return PointRule::centroid;
  throw InputError(fmt::format("unknown point creation rule '{}' (edge, centroid)", name));
}

const char* to_string(PointRule r) { return r == PointRule::edge ? "edge" : "centroid"; }

namespace {
template <class List>
void check_name(std::string_view what, const std::string& name) {
  if (!List::contains(name)) throw InputError(fmt::format("unknown {} '{}' ({})", what, name, List::names()));
}
}  // namespace

void check_policy_choice(const PolicyChoice& c) {
  check_name<Spaces>("space", c.space);
  check_name<Precisions>("precision", c.precision);
  check_name<Concurrencies>("concurrency", c.concurrency);
}

bool space_compiled(std::string_view space) {
  return !METRICA_ADAPT_FIRST_SPACE_ONLY || space == Spaces::at<0>::name;
}

AdaptReport adapt(Mesh& mesh, const AdaptOptions& options, const PolicyChoice& p) {
  return with_policy<Spaces>("space", p.space, [&]<class S>() {
    return with_policy<Concurrencies>("concurrency", p.concurrency, [&]<class C>() -> AdaptReport {
      if constexpr (METRICA_ADAPT_FIRST_SPACE_ONLY && !std::is_same_v<S, Spaces::at<0>>) {
        throw InputError(fmt::format("space '{}': this build compiles the pipeline for the space '{}' only "
                                     "(METRICA_ADAPT_FIRST_SPACE_ONLY, a sanitizer build)",
                                     S::name, Spaces::at<0>::name));
      } else {
        if (options.geometry != nullptr) return adapt_instance<S, C, CadGeometry>(mesh, options, p.precision);
        return adapt_instance<S, C, NoGeometry>(mesh, options, p.precision);
      }
    });
  });
}

}  // namespace metrica
