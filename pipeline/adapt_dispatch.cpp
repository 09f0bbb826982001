#include <metrica/error.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <fmt/core.h>

#include <type_traits>

namespace metrica {

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

std::string not_compiled_message(std::string_view what, std::string_view name, std::string_view compiled) {
  return fmt::format(
      "{} '{}': this build compiles the pipeline for the {} '{}' only "
      "(METRICA_DEFAULT_POLICIES_ONLY, METRICA_SPECULATIVE_ONLY: the sanitizer builds and scripts/demo's; "
      "scripts/build compiles every policy)",
      what, name, what, compiled);
}

bool policies_compiled(const PolicyChoice& p) {
  return (!METRICA_DEFAULT_POLICIES_ONLY ||
          (p.space == Spaces::at<0>::name && p.precision == Precisions::at<0>::name)) &&
         (!METRICA_SPECULATIVE_ONLY || p.concurrency == Concurrencies::at<0>::name);
}

AdaptReport adapt_by_name(Mesh& mesh, const AdaptOptions& options, const PolicyChoice& p, const AdaptInputs& inputs) {
  return with_policy<Spaces>("space", p.space, [&]<class S>() {
    return with_policy<Concurrencies>("concurrency", p.concurrency, [&]<class C>() -> AdaptReport {
      if constexpr (METRICA_DEFAULT_POLICIES_ONLY && !std::is_same_v<S, Spaces::at<0>>) {
        throw InputError(not_compiled_message("space", S::name, Spaces::at<0>::name));
      } else if constexpr (METRICA_SPECULATIVE_ONLY && !std::is_same_v<C, Concurrencies::at<0>>) {
        throw InputError(not_compiled_message("concurrency", C::name, Concurrencies::at<0>::name));
      } else {
        return adapt_instance<S, C, ModelOrFacets>(mesh, options, inputs, p.precision);
      }
    });
  });
}

}  // namespace metrica
