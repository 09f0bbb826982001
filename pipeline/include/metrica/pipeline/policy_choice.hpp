// The policies of an adaptation chosen at run time by name (the command's
// --space, --precision and --concurrency, Python's keyword arguments), one
// name from each policy list (Spaces, Precisions, Concurrencies).
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/predicates/precision.hpp>

#include <string>
#include <string_view>

namespace metrica {

struct PolicyChoice {
  std::string space{Spaces::at<0>::name};
  std::string precision{Precisions::at<0>::name};
  std::string concurrency{Concurrencies::at<0>::name};
};

// InputError naming the choices when a name is not in its list.
void check_policy_choice(const PolicyChoice& choice);
// False for a choice whose pipeline this build leaves out
// (METRICA_DEFAULT_POLICIES_ONLY, METRICA_SPECULATIVE_ONLY: the sanitizer builds).
bool policies_compiled(const PolicyChoice& choice);
// "space 'isotropic': this build compiles the pipeline for the space
// 'log-euclidean' only (...)".
std::string not_compiled_message(std::string_view what, std::string_view name, std::string_view compiled);

}  // namespace metrica
