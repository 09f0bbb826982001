#include "adaptation.hpp"

#include "fields.hpp"
#include "messages.hpp"

#include <metrica/allocator.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/pipeline/predicted_size.hpp>
#include <metrica/policies/threads.hpp>

#include <fmt/core.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <pybind11/stl.h>

namespace metrica::python {

namespace {

py::dict stats_dict(const OperatorStats& s) {
  return py::dict(py::arg("tried") = s.tried, py::arg("applied") = s.applied, py::arg("rejected") = s.rejected,
                  py::arg("deferred") = s.deferred, py::arg("candidates") = s.candidates,
                  py::arg("conflicts") = s.conflicts, py::arg("seconds") = s.seconds);
}

py::dict ops_dict(const OperatorReport& r) {
  py::dict out;
  for (const auto& [name, s] : r) out[py::str(name)] = stats_dict(s);
  return out;
}

py::dict cycle_dict(const CycleReport& c) {
  return py::dict(py::arg("kind") = c.repair          ? "repair"
                                    : c.quality_phase ? "polish"
                                                      : "cycle",
                  py::arg("cycle") = c.cycle, py::arg("vertices") = c.vertices, py::arg("tets") = c.tets,
                  py::arg("in_range") = c.conformity_measured ? py::object(py::float_(c.conformity)) : py::none(),
                  py::arg("min_quality") = c.min_quality, py::arg("seconds") = c.seconds,
                  py::arg("ops") = ops_dict(c.ops));
}

py::dict sample_dict(const SampleStats& s) {
  return py::dict(py::arg("min") = s.min, py::arg("mean") = s.mean, py::arg("max") = s.max, py::arg("count") = s.count);
}

py::dict histogram_dict(const Histogram& h) {
  return py::dict(py::arg("edges") = h.edges, py::arg("counts") = h.counts, py::arg("below") = h.below,
                  py::arg("above") = h.above);
}

py::dict quality_dict(const QualityReport& q) {
  py::dict out;
  out["space"] = q.space;
  out["vertices"] = q.vertices;
  out["edges"] = q.edges;
  out["tets"] = q.tets;
  out["length"] = sample_dict(q.length);
  out["mean_ratio"] = sample_dict(q.quality);
  out["unit_length_share"] = q.unit_length_share;
  out["quality_below_0.1"] = q.quality_below_01;
  out["quality_below_0.3"] = q.quality_below_03;
  out["complexity"] = q.complexity;
  out["vertices_per_complexity"] = q.vertices_per_complexity;
  out["volume"] = q.volume;
  out["length_histogram"] = histogram_dict(q.length_histogram);
  out["mean_ratio_histogram"] = histogram_dict(q.quality_histogram);
  return out;
}

// The options of `metrica adapt` by their Python names (the settings
// table's, '_' for '-'), checked against the same ranges.
AdaptOptions adapt_options(const py::dict& options, MetricBounds& bounds) {
  AdaptOptions o;
  py::object hmin = py::none(), hmax = py::none();
  for (const auto& [key, value] : options) {
    const auto name = key.cast<std::string>();
    const auto setting = name.find('-') == std::string::npos ? adapt_setting(name) : std::nullopt;
    if (setting) {
      const double x = value.cast<double>();
      if (!setting->accepts(x))
        throw InputError(fmt::format("adapt: {} must be {} (got {})", name, setting->domain(), x));
      setting->set(o, x);
    } else if (name == "points") {
      o.points = point_rule_from_name(value.cast<std::string>());
    } else if (name == "hmin") {
      hmin = py::reinterpret_borrow<py::object>(value);
    } else if (name == "hmax") {
      hmax = py::reinterpret_borrow<py::object>(value);
    } else {
      throw InputError(fmt::format("adapt: unknown option '{}' ({}, points, hmin, hmax)", name, adapt_setting_names()));
    }
  }
  try {
    check_length_band(o, "min_length", "max_length");
  } catch (const InputError& e) {
    throw InputError(fmt::format("adapt: {}", e.what()));
  }
  bounds = bounds_of(hmin, hmax);
  return o;
}

}  // namespace

ThreadsForCall::ThreadsForCall(int threads) {
  if (threads <= 0) return;
  previous_ = thread_count();
  set_thread_count(threads);
}

ThreadsForCall::~ThreadsForCall() {
  if (previous_ > 0) set_thread_count(previous_);
}

std::function<void(const CycleReport&)> cycle_callback(py::list& cycles, const py::object& on_cycle) {
  // By address: the function is copied without the GIL, a Python object
  // may not be.
  return [cycles = &cycles, on_cycle = &on_cycle](const CycleReport& c) {
    py::gil_scoped_acquire gil;
    cycles->append(cycle_dict(c));
    try {
      if (!on_cycle->is_none()) (*on_cycle)((*cycles)[py::len(*cycles) - 1]);
    } catch (py::error_already_set& e) {
      e.restore();
      throw PythonError{};
    }
    if (PyErr_CheckSignals() != 0) throw PythonError{};
  };
}

py::dict adapt_report(const py::list& cycles, const OperatorReport& ops, double seconds, const QualityReport& q) {
  py::dict report;
  report["cycles"] = cycles;
  report["ops"] = ops_dict(ops);
  report["seconds"] = seconds;
  report["quality"] = quality_dict(q);
  return report;
}

py::dict quality(const PyMesh& m, const py::object& metric, const std::string& space, bool measures,
                 const py::object& metric_mesh) {
  if (metric.is_none()) throw InputError("quality: give the metric, an (n, 6) array");
  Mesh mesh = m.mesh();
  if (metric_mesh.is_none()) {
    assign_metric(mesh, metric_by_id(mesh, metric));
  } else {
    // The metric at the vertices of another mesh, interpolated
    // log-Euclidean at this one's.
    const Mesh& on = metric_mesh.cast<const PyMesh&>().mesh();
    BackgroundMetric(on, metric_by_id(on, metric)).assign(mesh);
  }
  py::dict out = quality_dict(quality_report(mesh, space));
  if (!measures) return out;
  const QualityMeasures q = quality_measures(mesh, space);
  // Vertex ids to the arrays' indices (removed vertices skipped).
  std::vector<std::int32_t> index(mesh.vertex_capacity(), -1);
  std::int32_t next = 0;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) index[v] = next++;
  py::array_t<std::int32_t> edges({static_cast<py::ssize_t>(q.edges.size()), py::ssize_t{2}});
  std::int32_t* e = edges.mutable_data();
  for (const auto& [a, b] : q.edges) {
    *e++ = index[a];
    *e++ = index[b];
  }
  out["edge_ends"] = edges;
  out["edge_lengths"] = py::array_t<double>(static_cast<py::ssize_t>(q.lengths.size()), q.lengths.data());
  out["mean_ratios"] = py::array_t<double>(static_cast<py::ssize_t>(q.mean_ratios.size()), q.mean_ratios.data());
  return out;
}

py::tuple adapt(const PyMesh& m, const AdaptCall& call) {
  MetricBounds bounds;
  const AdaptOptions ao = adapt_options(call.options, bounds);
  PolicyChoice policies;
  if (!call.space.empty()) policies.space = call.space;
  if (!call.precision.empty()) policies.precision = call.precision;
  if (!call.concurrency.empty()) policies.concurrency = call.concurrency;
  check_policy_choice(policies);
  if (call.iterations < 1 || call.iterations > 1000)
    throw InputError(fmt::format("adapt: iterations must be in [1, 1000] (got {})", call.iterations));
  if (call.analytic.empty() == call.metric.is_none())
    throw InputError("adapt: give one of metric (an (n, 6) array) or analytic (a name)");
  if (call.iterations > 1 && call.analytic.empty())
    throw InputError("adapt: iterations > 1 needs analytic (an array holds values at the input's vertices only)");
  if (call.threads < 0 || call.threads > 4096)
    throw InputError(fmt::format("adapt: threads must be in [1, 4096] (got {})", call.threads));
  if (!(call.max_tets >= 0))
    throw InputError(fmt::format("adapt: max_tets must be a positive number (got {})", call.max_tets));
  const ThreadsForCall threads(call.threads);

  // One adaptation of the input; as the command, a threaded run that fails
  // its end check is made again serially (adapted_check.hpp).
  const auto attempt = [&](const PolicyChoice& chosen) -> py::tuple {
    Mesh mesh = m.mesh();  // the input stays as it was, whatever happens
    const double volume = mesh.volume();
    std::optional<AnalyticMetric> kind;
    MetricFunction exact;
    AdaptInputs inputs;
    // On a CAD model, as `metrica adapt --geometry`: the boundary vertices
    // associated with their entities (from the mesh's own records when its
    // ids are the arrays' indices, as for a mesh read or built from arrays).
    std::unique_ptr<CadModel> model;
    if (!call.geometry.empty()) {
      model = std::make_unique<CadModel>(call.geometry);
      const bool compact = mesh.vertex_capacity() == mesh.num_vertices();
      associate(mesh, *model, compact ? &m.data() : nullptr);
      inputs.model = model.get();
    }
    std::vector<Sym6> given;
    if (!call.analytic.empty()) {
      kind = analytic_metric_from_name(call.analytic);
      if (bounds.active())
        exact = [k = *kind, bounds](const Point& p) { return clamp_metric(evaluate(k, p), bounds); };
      else
        exact = [k = *kind](const Point& p) { return evaluate(k, p); };
      inputs.metric = &exact;
    } else {
      given = metric_by_id(mesh, call.metric, "metric", false);
    }
    // The size predicted once, before any work, as the command does.
    const PredictedSize size = check_predicted_size(
        kind ? sampled_complexity(mesh, exact) : complexity(mesh, given), call.max_tets, "adapt", "the metric",
        "max_tets=N raises it; the default is what 90% of this machine's memory holds");
    if (call.dry_run) {
      py::dict prediction;
      prediction["complexity"] = size.complexity;
      prediction["predicted_tets"] = size.tets;
      prediction["predicted_bytes"] = size.bytes;
      return py::make_tuple(py::none(), prediction);
    }
    // An array's field stays, on the input mesh, the background of the run.
    std::unique_ptr<BackgroundMetric> background;
    py::list cycles;
    inputs.on_cycle = cycle_callback(cycles, call.on_cycle);
    OperatorReport ops;
    double seconds = 0.0;
    QualityReport q;
    const MessagesDelivered delivered;  // those of the threads, once the GIL is back
    try {
      py::gil_scoped_release no_gil;
      const FreedMemoryKeptForRun memory;  // as the command's (allocator.hpp)
      for (int it = 0; it < call.iterations; ++it) {
        std::vector<Sym6> field = kind ? analytic_metric_field(*kind, vertex_points(mesh)) : given;
        clamp_metrics(field, bounds);
        check_metric_field(field, kind ? fmt::format("metric '{}'", call.analytic) : std::string("metric"));
        assign_metric(mesh, field);
        if (!kind && it == 0) {
          background = std::make_unique<BackgroundMetric>(mesh);
          inputs.background = background.get();
        }
        const AdaptReport report = adapt_by_name(mesh, ao, chosen, inputs);
        ops += report.ops;
        seconds += report.seconds;
      }
      // The report (and the metric of the returned mesh) in the field given.
      if (background) background->assign(mesh);
      require_adapted(mesh, model.get(), volume, adapted_volume_tolerance(call.iterations, ao.volume_budget));
      q = quality_report(mesh, chosen.space, {.cached_quality = true});
    } catch (const PythonError&) {
      throw py::error_already_set();
    }
    return py::make_tuple(py::cast(PyMesh(std::move(mesh), m.version()), py::return_value_policy::move),
                          adapt_report(cycles, ops, seconds, q));
  };
  return adapt_or_again_serially(policies, "from the input under concurrency=\"serial\"", attempt);
}

}  // namespace metrica::python
