// The stages a pipeline may be composed of, by operation name: each kind
// with its options (name, kind, range, help) and how a Stage is made from
// the values given. Python's Pipeline (its stage lists and its docstring)
// is made from this table; a new kind of stage is one entry here.
#pragma once

#include <metrica/error.hpp>
#include <metrica/operators/criterion.hpp>
#include <metrica/pipeline/adapter.hpp>
#include <metrica/policy_list.hpp>

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace metrica {

// One option of a stage kind: a number in [lo, hi], a whole number in
// [lo, hi], a flag, or a name among `choices`.
struct StageOption {
  enum class Kind { number, count, flag, choice };
  std::string_view name;
  Kind kind;
  double lo = 0, hi = 0;
  std::string_view help;
  std::string_view choices = {};  // a choice's names, comma-separated
  // "a number in [0, 1]", "a whole number in [1, 1000]", "true or false", "min-quality, ...".
  std::string domain() const {
    switch (kind) {
      case Kind::number: return fmt::format("a number in [{:g}, {:g}]", lo, hi);
      case Kind::count: return fmt::format("a whole number in [{:g}, {:g}]", lo, hi);
      case Kind::flag: return "true or false";
      case Kind::choice: return std::string(choices);
    }
    return {};
  }
};

// The values given for one stage's options, by name.
using StageValue = std::variant<double, bool, std::string>;
using StageValues = std::map<std::string, StageValue, std::less<>>;

// Reads a stage's values into an operation's options: each given value
// checked against its option (kind and range), an unknown name an error
// naming the stage and the options its kind has.
class StageArguments {
 public:
  StageArguments(std::string_view stage, std::string_view op, const std::vector<StageOption>& options,
                 const StageValues& values)
      : stage_(stage), options_(options), values_(values) {
    for (const auto& [name, value] : values)
      if (!option(name))
        throw InputError(fmt::format("stage '{}' ({}): unknown option '{}' ({})", stage, op, name, known()));
  }
  void number(std::string_view name, double& into) const {
    if (const double* x = get<double>(name)) into = *x;
  }
  void count(std::string_view name, int& into) const {
    if (const double* x = get<double>(name)) into = int(*x);
  }
  void flag(std::string_view name, bool& into) const {
    if (const bool* x = get<bool>(name)) into = *x;
  }
  std::string choice(std::string_view name, std::string_view fallback) const {
    const std::string* x = get<std::string>(name);
    return x ? *x : std::string(fallback);
  }

 private:
  const StageOption* option(std::string_view name) const {
    for (const auto& o : options_)
      if (o.name == name) return &o;
    return nullptr;
  }
  std::string known() const {
    std::string k;
    for (const auto& o : options_) k += (k.empty() ? "" : ", ") + std::string(o.name);
    return k.empty() ? "none" : k;
  }
  template <class T>
  const T* get(std::string_view name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return nullptr;
    const StageOption& o = *option(name);
    const T* x = std::get_if<T>(&it->second);
    const auto bad = [&] { return InputError(fmt::format("stage '{}': {} must be {}", stage_, name, o.domain())); };
    if (!x) throw bad();
    if constexpr (std::is_same_v<T, double>) {
      if (!(*x >= o.lo && *x <= o.hi)) throw bad();
      if (o.kind == StageOption::Kind::count && std::floor(*x) != *x) throw bad();
    }
    return x;
  }
  std::string_view stage_;
  const std::vector<StageOption>& options_;
  const StageValues& values_;
};

// A kind of stage: the operation's name, what it does, its options, and
// the Stage it makes (named `name`, its report key).
template <class A>
struct StageKind {
  std::string_view op;
  std::string_view help;
  std::vector<StageOption> options;
  Stage<A> (*make)(const std::string& name, const StageArguments& args);
};

namespace stage_kinds_detail {

inline constexpr double kLongest = 1e6;  // a length bound no metric reaches
using K = StageOption::Kind;

inline std::vector<StageOption> refine_options() {
  return {{"max_length", K::number, 0, kLongest, "split edges longer than this in the metric"},
          {"min_new_distance", K::number, 0, kLongest, "no new vertex nearer than this to another"},
          {"shape_floor", K::number, 0, 1, "no new tet below this mean ratio"}};
}
inline RefineOptions refine_from(const StageArguments& a) {
  RefineOptions r;
  a.number("max_length", r.max_length);
  a.number("min_new_distance", r.min_new_distance);
  a.number("shape_floor", r.shape_floor);
  return r;
}

}  // namespace stage_kinds_detail

// Every kind of stage, in the order help lists them.
template <class A>
const std::vector<StageKind<A>>& stage_kinds() {
  using namespace stage_kinds_detail;
  static const std::string criteria = FlipCriteria::names();
  static const std::vector<StageKind<A>> kinds{
      {"collapse",
       "edge collapses of the short edges",
       {{"min_length", K::number, 0, kLongest, "collapse edges shorter than this in the metric"},
        {"max_new_length", K::number, 0, kLongest, "no edge longer than this made"},
        {"shape_floor", K::number, 0, 1, "no tet below this mean ratio made"}},
       [](const std::string& name, const StageArguments& a) -> Stage<A> {
         CollapseOptions c;
         a.number("min_length", c.min_length);
         a.number("max_new_length", c.max_new_length);
         a.number("shape_floor", c.shape_floor);
         return {name, [c](A& ad) { return ad.collapse(c); }};
       }},
      {"split", "edge splits of the long edges at their metric midpoints", refine_options(),
       [](const std::string& name, const StageArguments& a) -> Stage<A> {
         const RefineOptions r = refine_from(a);
         return {name, [r](A& ad) { return ad.split(r); }};
       }},
      {"centroids", "insertion at the centroids of the tets with long edges (the paper's point rule)", refine_options(),
       [](const std::string& name, const StageArguments& a) -> Stage<A> {
         const RefineOptions r = refine_from(a);
         return {name, [r](A& ad) { return ad.insert_centroids(r); }};
       }},
      {"flip",
       "flips (2-3, 3-2, edge removal, 4-4) under a criterion",
       {{"criterion", K::choice, 0, 0, "which configuration a flip prefers", criteria},
        {"seed_below", K::number, 0, 1, "start at the tets below this mean ratio"},
        {"max_sweeps", K::count, 1, 1000, "sweeps at most"},
        {"face_flips", K::flag, 0, 0, "try 2-3 face flips too"},
        {"face_flip_below", K::number, 0, 1, "face flips at tets below this mean ratio"}},
       [](const std::string& name, const StageArguments& a) -> Stage<A> {
         ReconnectOptions r;
         a.number("seed_below", r.seed_below);
         a.count("max_sweeps", r.max_sweeps);
         a.flag("face_flips", r.face_flips);
         a.number("face_flip_below", r.face_flip_below);
         return with_policy<FlipCriteria>(
             fmt::format("criterion of stage '{}'", name), a.choice("criterion", MinQuality::name),
             [&]<class Criterion>() -> Stage<A> {
               return {name, [r, name](A& ad) { return ad.template flips<Criterion>(r, name); }};
             });
       }},
      {"smooth",
       "vertex smoothing of the balls of poor tets",
       {{"below", K::number, 0, 1, "move the vertices of tets below this mean ratio"},
        {"shape_floor", K::number, 0, 1, "no tet below this mean ratio made"}},
       [](const std::string& name, const StageArguments& a) -> Stage<A> {
         SmoothOptions m;
         a.number("below", m.below);
         a.number("shape_floor", m.shape_floor);
         return {name, [m, name](A& ad) { return ad.smooth(m, name); }};
       }},
      {"swap",
       "the internal surfaces' 2-2 swaps and flips",
       {},
       [](const std::string& name, const StageArguments&) -> Stage<A> {
         return {name, [](A& ad) { return ad.swap_interfaces(); }};
       }},
  };
  return kinds;
}

// The kind of stage `op`; InputError naming the kinds when there is none.
template <class A>
const StageKind<A>& stage_kind(std::string_view op, std::string_view stage) {
  std::string names;
  for (const auto& k : stage_kinds<A>()) {
    if (k.op == op) return k;
    names += (names.empty() ? "" : ", ") + std::string(k.op);
  }
  throw InputError(fmt::format("stage '{}': unknown operation '{}' ({})", stage, op, names));
}

// The stage `name` of operation `op` with the options given.
template <class A>
Stage<A> make_stage(const std::string& name, std::string_view op, const StageValues& values) {
  const StageKind<A>& kind = stage_kind<A>(op, name);
  return kind.make(name, StageArguments(name, op, kind.options, values));
}

}  // namespace metrica
