#include "pipeline.hpp"

#include "adaptation.hpp"
#include "fields.hpp"

#include <metrica/allocator.hpp>
#include <metrica/error.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/policies/threads.hpp>

#include <fmt/core.h>

#include <memory>
#include <optional>
#include <set>

namespace metrica::python {

namespace {

// The options of one stage, each taken once: unknown names are an error
// naming the stage and the names it knows.
class StageOptions {
 public:
  StageOptions(const StageSpec& s, std::string known) : spec_(s), known_(std::move(known)) {
    for (const auto& [k, v] : s.options) left_.insert(k.cast<std::string>());
  }
  template <class T>
  void take(const char* name, T& into) {
    if (!left_.erase(name)) return;
    into = spec_.options[name].template cast<T>();
  }
  void number(const char* name, double& into, double lo, double hi) {
    if (!left_.count(name)) return;
    take(name, into);
    if (!(into >= lo && into <= hi))
      throw InputError(fmt::format("stage '{}': {} must be in [{}, {}] (got {})", spec_.name, name, lo, hi, into));
  }
  std::string text(const char* name, std::string fallback) {
    take(name, fallback);
    return fallback;
  }
  void done() const {
    if (!left_.empty())
      throw InputError(fmt::format("stage '{}' ({}): unknown option '{}' ({})", spec_.name, spec_.op, *left_.begin(),
                                   known_.empty() ? std::string("none") : known_));
  }

 private:
  const StageSpec& spec_;
  std::string known_;
  std::set<std::string> left_;
};

template <class A>
Stage<A> make_stage(const StageSpec& s) {
  constexpr double kBig = 1e6;
  if (s.op == "collapse") {
    StageOptions o(s, "min_length, max_new_length, shape_floor");
    CollapseOptions c;
    o.number("min_length", c.min_length, 0.0, kBig);
    o.number("max_new_length", c.max_new_length, 0.0, kBig);
    o.number("shape_floor", c.shape_floor, 0.0, 1.0);
    o.done();
    return {s.name, [c](A& a) { return a.collapse(c); }};
  }
  if (s.op == "split" || s.op == "centroids") {
    StageOptions o(s, "max_length, min_new_distance, shape_floor");
    RefineOptions r;
    o.number("max_length", r.max_length, 0.0, kBig);
    o.number("min_new_distance", r.min_new_distance, 0.0, kBig);
    o.number("shape_floor", r.shape_floor, 0.0, 1.0);
    o.done();
    if (s.op == "split") return {s.name, [r](A& a) { return a.split(r); }};
    return {s.name, [r](A& a) { return a.insert_centroids(r); }};
  }
  if (s.op == "flip") {
    StageOptions o(s, "criterion, seed_below, max_sweeps, face_flips, face_flip_below");
    ReconnectOptions r;
    const std::string criterion = o.text("criterion", "min-quality");
    o.number("seed_below", r.seed_below, 0.0, 1.0);
    double sweeps = r.max_sweeps;
    o.number("max_sweeps", sweeps, 1.0, 1000.0);
    r.max_sweeps = static_cast<int>(sweeps);
    o.take("face_flips", r.face_flips);
    o.number("face_flip_below", r.face_flip_below, 0.0, 1.0);
    o.done();
    const std::string key = s.name;
    // "unknown criterion of stage 'flip' 'delaunay' (min-quality, ...)".
    return with_policy<FlipCriteria>(fmt::format("criterion of stage '{}'", key), criterion,
                                     [&]<class Criterion>() -> Stage<A> {
                                       return {s.name, [r, key](A& a) { return a.template flips<Criterion>(r, key); }};
                                     });
  }
  if (s.op == "smooth") {
    StageOptions o(s, "below, shape_floor");
    SmoothOptions m;
    o.number("below", m.below, 0.0, 1.0);
    o.number("shape_floor", m.shape_floor, 0.0, 1.0);
    o.done();
    const std::string key = s.name;
    return {s.name, [m, key](A& a) { return a.smooth(m, key); }};
  }
  if (s.op == "swap") {
    StageOptions(s, "").done();
    return {s.name, [](A& a) { return a.swap_interfaces(); }};
  }
  throw InputError(
      fmt::format("stage '{}': unknown operation '{}' (collapse, split, centroids, flip, smooth, swap)", s.name, s.op));
}

template <class A>
Stages<A> make_stages(const std::vector<StageSpec>& specs) {
  Stages<A> out;
  std::set<std::string> names;
  for (const auto& s : specs) {
    if (!names.insert(s.name).second)
      throw InputError(fmt::format("two stages named '{}' in one list (a stage's name is its report key)", s.name));
    out.push_back(make_stage<A>(s));
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
