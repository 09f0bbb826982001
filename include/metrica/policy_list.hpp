// Lists of policies, chosen by name at run time: the CLI's --space,
// --precision and --concurrency. A policy is listed once (Spaces in
// metrics/space.hpp, Precisions in predicates/precision.hpp, Concurrencies
// in policies/speculative.hpp); dispatch, the names in messages and the
// pipeline's compiled instances all follow the lists.
#pragma once

#include <metrica/error.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>

namespace metrica {

template <class... T>
struct PolicyList {
  static constexpr std::size_t size = sizeof...(T);
  template <std::size_t I>
  using at = std::tuple_element_t<I, std::tuple<T...>>;
  // "a, b, c"
  static std::string names() {
    std::string out;
    ((out += (out.empty() ? "" : ", ") + std::string(T::name)), ...);
    return out;
  }
  static bool contains(std::string_view name) { return ((T::name == name) || ...); }
};

template <class... T, class F>
auto with_policy_in(PolicyList<T...>, std::string_view what, std::string_view name, F&& f) {
  using First = std::tuple_element_t<0, std::tuple<T...>>;
  std::optional<decltype(f.template operator()<First>())> result;
  static_cast<void>(((T::name == name && (result.emplace(f.template operator()<T>()), true)) || ...));
  if (!result)
    throw InputError("unknown " + std::string(what) + " '" + std::string(name) + "' (" + PolicyList<T...>::names() +
                     ")");
  return std::move(*result);
}

// f.template operator()<T>() for the policy T of `List` called `name`;
// InputError naming the choices when there is none.
template <class List, class F>
auto with_policy(std::string_view what, std::string_view name, F&& f) {
  return with_policy_in(List{}, what, name, std::forward<F>(f));
}

}  // namespace metrica
