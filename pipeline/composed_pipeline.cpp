#include <metrica/error.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/pipeline/composed_pipeline.hpp>
#include <metrica/pipeline/policy_choice.hpp>
#include <metrica/pipeline/standard_stages.hpp>

#include <fmt/core.h>

#include <charconv>
#include <memory>
#include <set>
#include <type_traits>

namespace metrica {

namespace {

std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// true, false, a number (the whole text), else the text as a name.
StageValue value_of(std::string_view text) {
  if (text == "true") return true;
  if (text == "false") return false;
  double x = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (error == std::errc() && end == text.data() + text.size()) return x;
  return std::string(text);
}

StageSpec parse_stage(std::string_view text, std::string_view list) {
  const auto bad = [&](std::string_view why) {
    return InputError(fmt::format("{}: stage '{}': {} (a stage is [NAME=]OP[:OPTION=VALUE]...)", list, text, why));
  };
  StageSpec s;
  std::string_view head = text.substr(0, text.find(':'));
  if (const auto eq = head.find('='); eq != std::string_view::npos) {
    s.name = trimmed(head.substr(0, eq));
    head = head.substr(eq + 1);
    if (s.name.empty()) throw bad("an empty name before '='");
  }
  s.op = trimmed(head);
  if (s.op.empty()) throw bad("no operation");
  if (s.name.empty()) s.name = s.op;
  for (std::size_t at = text.find(':'); at != std::string_view::npos;) {
    const std::size_t next = text.find(':', at + 1);
    const std::string_view option = trimmed(text.substr(at + 1, next == std::string_view::npos ? next : next - at - 1));
    const auto eq = option.find('=');
    if (eq == std::string_view::npos || trimmed(option.substr(0, eq)).empty() || trimmed(option.substr(eq + 1)).empty())
      throw bad(fmt::format("'{}' is not OPTION=VALUE", option));
    const std::string name(trimmed(option.substr(0, eq)));
    if (!s.values.emplace(name, value_of(trimmed(option.substr(eq + 1)))).second)
      throw bad(fmt::format("option '{}' given twice", name));
    at = next;
  }
  return s;
}

template <class A>
Stages<A> make_stages(const std::vector<StageSpec>& specs) {
  Stages<A> out;
  std::set<std::string, std::less<>> names;
  for (const auto& s : specs) {
    if (!names.insert(s.name).second)
      throw InputError(fmt::format("two stages named '{}' in one list (a stage's name is its report key)", s.name));
    out.push_back(make_stage<A>(s.name, s.op, s.values));
  }
  return out;
}

template <class A>
Pipeline<A> make_pipeline(const ComposedPipeline& spec) {
  Pipeline<A> p;
  static_cast<PipelineRules&>(p) = spec.rules;
  p.cycle = make_stages<A>(spec.cycle);
  p.polish = make_stages<A>(spec.polish);
  p.repair = make_stages<A>(spec.repair);
  if (p.cycle.empty() && p.polish.empty() && p.repair.empty()) throw InputError("pipeline: no stage to run");
  return p;
}

}  // namespace

const std::vector<StageKindInfo>& stage_kind_infos() {
  static const std::vector<StageKindInfo> infos = [] {
    std::vector<StageKindInfo> out;
    for (const auto& k : stage_kinds<Adapter<LogEuclidean, Concurrencies::at<0>>>())
      out.push_back({k.op, k.help, k.options});
    return out;
  }();
  return infos;
}

const StageKindInfo& stage_kind_info(std::string_view op, std::string_view stage) {
  using Kinds = Adapter<LogEuclidean, Concurrencies::at<0>>;
  // The registry's refusal when there is no such kind; the infos are in
  // the registry's order.
  const StageKind<Kinds>& kind = stage_kind<Kinds>(op, stage);
  return stage_kind_infos()[std::size_t(&kind - stage_kinds<Kinds>().data())];
}

std::vector<StageSpec> parse_stage_list(std::string_view text, std::string_view list) {
  std::vector<StageSpec> out;
  if (trimmed(text).empty()) return out;
  for (std::size_t at = 0;;) {
    const std::size_t comma = text.find(',', at);
    const std::string_view stage = trimmed(text.substr(at, comma == std::string_view::npos ? comma : comma - at));
    if (stage.empty()) throw InputError(fmt::format("{}: an empty stage in '{}'", list, text));
    out.push_back(parse_stage(stage, list));
    if (comma == std::string_view::npos) return out;
    at = comma + 1;
  }
}

void check_composed(const ComposedPipeline& p) {
  static_cast<void>(make_pipeline<Adapter<LogEuclidean, Concurrencies::at<0>>>(p));
}

AdaptReport run_composed(Mesh& mesh, const ComposedPipeline& spec, const AdaptInputs& inputs,
                         std::string_view concurrency) {
  if (inputs.model != nullptr) throw InputError("pipeline: a composed pipeline runs off a model (no geometry)");
  return with_policy<Concurrencies>("concurrency", concurrency, [&]<class C>() -> AdaptReport {
    // The AddressSanitizer build compiles the default concurrency's
    // pipeline only (pipeline/CMakeLists.txt).
    if constexpr (METRICA_SPECULATIVE_ONLY && !std::is_same_v<C, Concurrencies::at<0>>) {
      throw InputError(not_compiled_message("concurrency", C::name, Concurrencies::at<0>::name));
    } else {
      using A = Adapter<LogEuclidean, C>;
      const Pipeline<A> p = make_pipeline<A>(spec);
      // Without a metric to follow, the mesh's own field on the input mesh.
      std::unique_ptr<BackgroundMetric> own;
      AdaptInputs in = inputs;
      if (!in.source()) in.background = (own = std::make_unique<BackgroundMetric>(mesh)).get();
      A a(mesh, in.source());
      a.set_volume_budget(AdaptOptions{}.volume_budget);
      a.on_cycle = in.on_cycle;
      AdaptReport report = run_pipeline(a, p);
      if (own) own->assign(mesh);  // the adapted mesh's metric in the field given
      return report;
    }
  });
}

}  // namespace metrica
