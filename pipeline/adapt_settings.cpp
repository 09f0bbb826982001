#include <metrica/error.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapt_settings.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <array>

namespace metrica {

namespace {
// Lengths are in metric units: 1e6 is past any sensible band.
constexpr double kMaxLengthSetting = 1e6;

// The pipeline's rules first (pipeline_rule_settings), then the standard
// stages' settings.
constexpr std::size_t kRules = 7;
constexpr std::array<AdaptSetting, 13> kAdaptSettings{{
    {"cycles", "N", 0, 1000, false, true, "most adaptation cycles per adaptation",
     [](const AdaptOptions& o) { return double(o.max_cycles); },
     [](AdaptOptions& o, double x) { o.max_cycles = static_cast<int>(x); }},
    {"quality-passes", "N", 0, 1000, false, true, "flip + smooth passes at the end",
     [](const AdaptOptions& o) { return double(o.quality_passes); },
     [](AdaptOptions& o, double x) { o.quality_passes = static_cast<int>(x); }},
    {"repair-rounds", "N", 0, 1000, false, true,
     "after the quality passes, at most N repair rounds (collapse, split, flips and smoothing in adapt) around "
     "the tets still below --repair-below (none after two in a row that leave the worst tet)",
     [](const AdaptOptions& o) { return double(o.repair_rounds); },
     [](AdaptOptions& o, double x) { o.repair_rounds = static_cast<int>(x); }},
    {"repair-below", "Q", 0, 1, false, false,
     "mean ratio below which a tet left by the quality passes gets repair rounds",
     [](const AdaptOptions& o) { return o.repair_below; }, [](AdaptOptions& o, double x) { o.repair_below = x; }},
    {"min-change", "R", 0, 1, false, false,
     "stop cycling when a cycle creates and removes fewer vertices than this share of the vertices",
     [](const AdaptOptions& o) { return o.min_change; }, [](AdaptOptions& o, double x) { o.min_change = x; }},
    {"min-conformity-gain", "R", 0, 1, false, false,
     "or, once --near-unit-conformity of the edges are in the unit band, when a cycle raises that share by "
     "less than this",
     [](const AdaptOptions& o) { return o.min_conformity_gain; },
     [](AdaptOptions& o, double x) { o.min_conformity_gain = x; }},
    {"near-unit-conformity", "R", 0, 1, false, false,
     "the share of edges in the unit band from which --min-conformity-gain may stop the cycles",
     [](const AdaptOptions& o) { return o.near_unit_conformity; },
     [](AdaptOptions& o, double x) { o.near_unit_conformity = x; }},
    {"max-length", "L", 0, kMaxLengthSetting, true, false, "split edges longer than L (sqrt 2)",
     [](const AdaptOptions& o) { return o.refine.max_length; },
     [](AdaptOptions& o, double x) { o.refine.max_length = x; }},
    {"min-length", "L", 0, kMaxLengthSetting, true, false, "collapse edges shorter than L (1/sqrt 2)",
     [](const AdaptOptions& o) { return o.collapse.min_length; },
     [](AdaptOptions& o, double x) { o.collapse.min_length = x; }},
    {"collapse-max-length", "L", 0, kMaxLengthSetting, true, false, "a collapse may not make an edge longer than L",
     [](const AdaptOptions& o) { return o.collapse.max_new_length; },
     [](AdaptOptions& o, double x) { o.collapse.max_new_length = x; }},
    {"shape-floor", "Q", 0, 1, false, false,
     "a collapse may not make a tet worse than Q (unless the ball was already worse)",
     [](const AdaptOptions& o) { return o.collapse.shape_floor; },
     [](AdaptOptions& o, double x) { o.collapse.shape_floor = x; }},
    {"split-floor", "Q", 0, 1, false, false,
     "a split beside a vertex no operation moves (required, on a kept surface, on a part's kept faces under "
     "mpirun) may not make a tet worse than Q (unless its parent was already worse); under mpirun at least 0.01",
     [](const AdaptOptions& o) { return o.refine.shape_floor; },
     [](AdaptOptions& o, double x) { o.refine.shape_floor = x; }},
    {"smooth-below", "Q", 0, 1, false, false, "smooth the vertices of tets with mean ratio below Q during the cycles",
     [](const AdaptOptions& o) { return o.smooth.below; }, [](AdaptOptions& o, double x) { o.smooth.below = x; }},
}};

}  // namespace

static_assert(kAdaptSettings[kRules - 1].name == "near-unit-conformity" && kAdaptSettings[kRules].name == "max-length",
              "the pipeline's rules are the table's first rows");

std::span<const AdaptSetting> adapt_settings() { return kAdaptSettings; }
std::span<const AdaptSetting> pipeline_rule_settings() { return std::span(kAdaptSettings).first(kRules); }

std::string AdaptSetting::domain() const {
  return fmt::format("{}in {}{}, {}]", integer ? "an integer " : "", lo_open ? "(" : "[", lo, hi);
}

std::string AdaptSetting::python_name() const {
  std::string s(name);
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

std::optional<AdaptSetting> adapt_setting(std::string_view name) {
  for (const AdaptSetting& s : kAdaptSettings)
    if (s.name == name || s.python_name() == name) return s;
  return std::nullopt;
}

std::string adapt_setting_names() {
  std::string out;
  for (const AdaptSetting& s : kAdaptSettings) out += (out.empty() ? "" : ", ") + s.python_name();
  return out;
}

void check_length_band(const AdaptOptions& o, std::string_view min_name, std::string_view max_name) {
  if (!(o.refine.max_length > o.collapse.min_length))
    throw InputError(
        fmt::format("need {} < {} (got {} and {})", min_name, max_name, o.collapse.min_length, o.refine.max_length));
}

}  // namespace metrica
