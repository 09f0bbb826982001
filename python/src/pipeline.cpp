#include "pipeline.hpp"

#include "adaptation.hpp"
#include "fields.hpp"

#include <metrica/allocator.hpp>
#include <metrica/error.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/pipeline/stage_registry.hpp>
#include <metrica/policies/threads.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <set>

namespace metrica::python {

namespace {

// A stage's options as its kind reads them (pipeline/stage_registry.hpp):
// each value cast to its option's type; a name the kind has not is left
// for the registry to refuse, naming the options it has.
StageValues stage_values(const StageSpec& s, const std::vector<StageOption>& options) {
  StageValues values;
  for (const auto& [key, value] : s.options) {
    const auto name = key.cast<std::string>();
    const auto it = std::find_if(options.begin(), options.end(), [&](const StageOption& o) { return o.name == name; });
    const auto wrong = [&](const StageOption& o) {
      return InputError(fmt::format("stage '{}': {} must be {} (got {})", s.name, name, o.domain(),
                                    py::repr(value).cast<std::string>()));
    };
    if (it == options.end()) {
      values[name] = std::string();
    } else if (it->kind == StageOption::Kind::flag) {
      if (!py::isinstance<py::bool_>(value)) throw wrong(*it);
      values[name] = value.cast<bool>();
    } else if (it->kind == StageOption::Kind::choice) {
      if (!py::isinstance<py::str>(value)) throw wrong(*it);
      values[name] = value.cast<std::string>();
    } else {
      if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)))
        throw wrong(*it);
      values[name] = value.cast<double>();
    }
  }
  return values;
}

template <class A>
Stages<A> make_stages(const std::vector<StageSpec>& specs) {
  Stages<A> out;
  std::set<std::string> names;
  for (const auto& s : specs) {
    if (!names.insert(s.name).second)
      throw InputError(fmt::format("two stages named '{}' in one list (a stage's name is its report key)", s.name));
    out.push_back(make_stage<A>(s.name, s.op, stage_values(s, stage_kind<A>(s.op, s.name).options)));
  }
  return out;
}

void apply_rules(PipelineRules& p, const py::dict& rules) {
  for (const auto& [key, value] : rules) {
    const auto name = key.cast<std::string>();
    auto count = [&] {
      const int n = value.cast<int>();
      if (n < 0 || n > 1000) throw InputError(fmt::format("pipeline: {} must be in [0, 1000] (got {})", name, n));
      return n;
    };
    auto share = [&] {
      const double x = value.cast<double>();
      if (!(x >= 0.0 && x <= 1.0)) throw InputError(fmt::format("pipeline: {} must be in [0, 1] (got {})", name, x));
      return x;
    };
    if (name == "max_cycles")
      p.max_cycles = count();
    else if (name == "quality_passes")
      p.quality_passes = count();
    else if (name == "repair_rounds")
      p.repair_rounds = count();
    else if (name == "repair_below")
      p.repair_below = share();
    else if (name == "min_change")
      p.min_change = share();
    else if (name == "min_conformity_gain")
      p.min_conformity_gain = share();
    else if (name == "near_unit_conformity")
      p.near_unit_conformity = share();
    else
      throw InputError(
          fmt::format("pipeline: unknown rule '{}' (max_cycles, quality_passes, repair_rounds, "
                      "repair_below, min_change, min_conformity_gain, near_unit_conformity)",
                      name));
  }
}

template <class C>
py::tuple run_with(const PyMesh& m, const PipelineCall& call) {
  using A = Adapter<LogEuclidean, C>;
  Pipeline<A> p;
  apply_rules(p, call.rules);
  p.cycle = make_stages<A>(call.cycle);
  p.polish = make_stages<A>(call.polish);
  p.repair = make_stages<A>(call.repair);
  if (p.cycle.empty() && p.polish.empty() && p.repair.empty()) throw InputError("pipeline: no stage to run");

  Mesh mesh = m.mesh();  // the input stays as it was
  const double volume = mesh.volume();
  MetricFunction exact;
  std::vector<Sym6> field;
  if (!call.analytic.empty()) {
    const AnalyticMetric kind = analytic_metric_from_name(call.analytic);
    exact = [kind](const Point& x) { return evaluate(kind, x); };
    field = analytic_metric_field(kind, vertex_points(mesh));
  } else {
    field = metric_by_id(mesh, call.metric);
  }
  check_metric_field(field, "metric");
  assign_metric(mesh, field);
  // An array's field stays, on the input mesh, the background of the run.
  std::unique_ptr<BackgroundMetric> background;
  if (!exact) background = std::make_unique<BackgroundMetric>(mesh);
  py::list cycles;
  const auto callback = cycle_callback(cycles, call.on_cycle);
  AdaptReport report;
  QualityReport q;
  try {
    py::gil_scoped_release no_gil;
    const FreedMemoryKeptForRun memory;  // as the command's (allocator.hpp)
    A adapter(mesh, exact ? MetricSource(&exact) : MetricSource(background.get()));
    adapter.set_volume_budget(AdaptOptions{}.volume_budget);
    adapter.on_cycle = callback;
    report = metrica::run_pipeline(adapter, p);
    if (background) background->assign(mesh);  // the report in the field given
    require_adapted(mesh, nullptr, volume, adapted_volume_tolerance(1, AdaptOptions{}.volume_budget));
    q = quality_report(mesh, LogEuclidean::name, {.cached_quality = true});
  } catch (const PythonError&) {
    throw py::error_already_set();
  }
  return py::make_tuple(py::cast(PyMesh(std::move(mesh), m.version()), py::return_value_policy::move),
                        adapt_report(cycles, report.ops, report.seconds, q));
}

}  // namespace

py::tuple run_pipeline(const PyMesh& m, const PipelineCall& call) {
  if (call.analytic.empty() == call.metric.is_none())
    throw InputError("pipeline: give one of metric (an (n, 6) array) or analytic (a name)");
  if (call.threads < 0 || call.threads > 4096)
    throw InputError(fmt::format("pipeline: threads must be in [1, 4096] (got {})", call.threads));
  const ThreadsForCall threads(call.threads);
  if (call.concurrency == Serial::name) return run_with<Serial>(m, call);
  if (call.concurrency == Speculative::name) return run_with<Speculative>(m, call);
  throw InputError(fmt::format("pipeline: unknown concurrency '{}' (serial, speculative)", call.concurrency));
}

}  // namespace metrica::python
