// The standard adaptation's numeric settings that users set by name, one
// row each: the command declares, reads and checks its options from these
// rows (so its help and docs/cli.md show them) and Python takes its
// keyword arguments from them ('-' written '_'), with the same ranges.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace metrica {

struct AdaptOptions;

struct AdaptSetting {
  std::string_view name;        // the command's --name
  std::string_view value_name;  // how the help shows its value: N, Q, L
  double lo, hi;                // the values accepted: [lo, hi], or (lo, hi] when lo_open
  bool lo_open;
  bool integer;
  std::string_view help;
  double (*get)(const AdaptOptions&);
  void (*set)(AdaptOptions&, double);

  bool accepts(double x) const {
    return (lo_open ? x > lo : x >= lo) && x <= hi && (!integer || x == static_cast<double>(static_cast<long>(x)));
  }
  // "in [0, 1000]", "in (0, 1e+06]", "an integer in [0, 1000]".
  std::string domain() const;
  // Python's keyword: the name with '_' for '-'.
  std::string python_name() const;
};

// Every row, in the order the command's help lists them.
std::span<const AdaptSetting> adapt_settings();

// The first rows, the pipeline's rules (PipelineRules: cycles,
// quality-passes, repair-rounds, repair-below, min-change,
// min-conformity-gain, near-unit-conformity): what a composed pipeline
// takes by name (composed_pipeline.hpp).
std::span<const AdaptSetting> pipeline_rule_settings();

// The row named `name` (the command's spelling or Python's); none when no
// row has that name.
std::optional<AdaptSetting> adapt_setting(std::string_view name);
// The rows' Python names, ", "-separated (for messages and docstrings).
std::string adapt_setting_names();
// InputError unless min_length < max_length (min_name and max_name: the
// two settings as the caller's user spells them).
void check_length_band(const AdaptOptions& o, std::string_view min_name, std::string_view max_name);

}  // namespace metrica
