#include "pipeline.hpp"

#include "adaptation.hpp"
#include "fields.hpp"
#include "messages.hpp"

#include <metrica/allocator.hpp>
#include <metrica/error.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/pipeline/composed_pipeline.hpp>
#include <metrica/policies/threads.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <optional>

namespace metrica::python {

namespace {

// A stage's options as its kind reads them (pipeline/stage_registry.hpp):
// each value cast to its option's type; a name the kind has not is left
// for the registry to refuse, naming the options it has.
StageValues stage_values(const PyStageSpec& s, const std::vector<StageOption>& options) {
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

// The stages of a list in the library's form.
std::vector<StageSpec> specs_of(const std::vector<PyStageSpec>& list) {
  std::vector<StageSpec> out;
  for (const auto& s : list) out.push_back({s.name, s.op, stage_values(s, stage_kind_info(s.op, s.name).options)});
  return out;
}

// The rules by their Python names (pipeline_rule_settings: the command's
// rows), each checked against its row's range; max_cycles is the older
// name of cycles.
PipelineRules rules_of(const py::dict& rules) {
  AdaptOptions o;
  for (const auto& [key, value] : rules) {
    std::string name = key.cast<std::string>();
    if (name == "max_cycles") name = "cycles";
    const auto rows = pipeline_rule_settings();
    const auto row =
        std::find_if(rows.begin(), rows.end(), [&](const AdaptSetting& s) { return s.python_name() == name; });
    if (row == rows.end()) {
      std::string names;
      for (const AdaptSetting& s : rows) names += (names.empty() ? "" : ", ") + s.python_name();
      throw InputError(fmt::format("pipeline: unknown rule '{}' ({})", name, names));
    }
    const bool number =
        !py::isinstance<py::bool_>(value) && (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value));
    const double x = number ? value.cast<double>() : 0.0;
    if (!number || !row->accepts(x))
      throw InputError(
          fmt::format("pipeline: {} must be {} (got {})", name, row->domain(), py::repr(value).cast<std::string>()));
    row->set(o, x);
  }
  return o;
}

py::tuple run_composed_on(const PyMesh& m, const PipelineCall& call) {
  ComposedPipeline p;
  p.rules = rules_of(call.rules);
  p.cycle = specs_of(call.cycle);
  p.polish = specs_of(call.polish);
  p.repair = specs_of(call.repair);
  check_composed(p);

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
  // An array's field: run_composed keeps it on the input mesh.
  AdaptInputs inputs;
  if (exact) inputs.metric = &exact;
  py::list cycles;
  inputs.on_cycle = cycle_callback(cycles, call.on_cycle);
  AdaptReport report;
  QualityReport q;
  const MessagesDelivered delivered;  // those of the threads, once the GIL is back
  try {
    py::gil_scoped_release no_gil;
    const FreedMemoryKeptForRun memory;  // as the command's (allocator.hpp)
    report = run_composed(mesh, p, inputs, call.concurrency);
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
  return run_composed_on(m, call);
}

}  // namespace metrica::python
