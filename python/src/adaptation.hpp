// The adaptation and its quality report from Python: what `metrica adapt`
// and `metrica quality` do, on a PyMesh and
// numpy arrays, with the command's checks, defaults and results.
#pragma once

#include "mesh_arrays.hpp"

#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>

#include <pybind11/functional.h>
#include <string>

namespace metrica::python {

// The UGAWG quality report of the mesh in `metric` ((n, 6)) as a dict;
// with `measures`, the measures too: "edge_ends" (k, 2) vertex indices,
// "edge_lengths" (k,), "mean_ratios" (one per tet, in the order of
// mesh.tets).
py::dict quality(const PyMesh& m, const py::object& metric, const std::string& space, bool measures,
                 const py::object& metric_mesh);

// What adapt() is told: the metric (an (n, 6) array, or an analytic name
// re-evaluated between iterations), the policies by name, the options of
// `metrica adapt` by their names, a model, and a callback per cycle.
struct AdaptCall {
  py::object metric;
  std::string analytic;
  int iterations = 1;
  int threads = 0;  // 0: the default
  std::string concurrency, space, precision;
  std::string geometry;
  py::dict options;
  py::object on_cycle;
  double max_tets = 0;  // 0: what 90% of the memory holds
  bool dry_run = false;
};

// Thrown from the cycle callback when Python has an error to raise (a
// signal's KeyboardInterrupt, or the callback's own exception): the error
// stays set in the thread's state, raised once the GIL is back.
struct PythonError {};

// The callback of every cycle, pass and round, called without the GIL:
// appends the cycle's dict to `cycles` (with the GIL), calls `on_cycle`
// with it, and throws PythonError when Python has an error to raise. Both
// must outlive the callback.
std::function<void(const CycleReport&)> cycle_callback(py::list& cycles, const py::object& on_cycle);

// The thread count for one call (`threads` > 0), the previous one back
// when the call ends, however it ends.
class ThreadsForCall {
 public:
  explicit ThreadsForCall(int threads);
  ~ThreadsForCall();
  ThreadsForCall(const ThreadsForCall&) = delete;
  ThreadsForCall& operator=(const ThreadsForCall&) = delete;

 private:
  int previous_ = 0;
};

// The report adapt() returns: cycles, operations, seconds, quality.
py::dict adapt_report(const py::list& cycles, const OperatorReport& ops, double seconds, const QualityReport& q);

// The adapted copy of the mesh and the report: per cycle what each
// operation did, and the quality report. A run predicted to make more than
// max_tets tets is refused before any work; with dry_run, (None, the
// prediction) and nothing run. Runs without the GIL; Ctrl-C
// (a pending signal, checked after each cycle) stops it with
// KeyboardInterrupt and leaves the input as it was.
py::tuple adapt(const PyMesh& m, const AdaptCall& call);

}  // namespace metrica::python
