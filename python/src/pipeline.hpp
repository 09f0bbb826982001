// A pipeline composed in Python: the registry's stages by name, each with
// its options, in the order given, under rules by name (when to stop
// cycling, quality passes, repair rounds), run by the library's
// run_composed (pipeline/composed_pipeline.hpp) as `metrica pipeline` runs
// the command line's.
#pragma once

#include "mesh_arrays.hpp"

#include <string>

namespace metrica::python {

// A stage: its name (its report key), the operation and its options (the
// registry's, stage_registry.hpp).
struct PyStageSpec {
  std::string name, op;
  py::dict options;
};

struct PipelineCall {
  py::object metric;     // (n, 6), or
  std::string analytic;  // an analytic metric's name
  std::vector<PyStageSpec> cycle, polish, repair;
  py::dict rules;  // by the Python names of pipeline_rule_settings()
  std::string concurrency;
  int threads = 0;
  py::object on_cycle;
};

// The adapted copy and its report, as adapt() returns them.
py::tuple run_pipeline(const PyMesh& m, const PipelineCall& call);

}  // namespace metrica::python
