// A pipeline composed in Python: the standard stages by name, each with its
// options (and a flip's criterion), in the order given, under the
// standard pipeline's rules (when to stop cycling, quality passes, repair
// rounds): what examples/compose does in C++, without a compiler.
#pragma once

#include "mesh_arrays.hpp"

#include <string>

namespace metrica::python {

// A stage: its name (its report key), the operation and its options.
//   collapse   min_length, max_new_length, shape_floor
//   split      max_length, min_new_distance, shape_floor (edge splits)
//   centroids  the same (centroid insertion)
//   flip       criterion ("min-quality", "metric-delaunay", "edge-weight"),
//              seed_below, max_sweeps, face_flips, face_flip_below
//   smooth     below, shape_floor
//   swap       (the internal surfaces' swaps and 2-2 flips)
struct StageSpec {
  std::string name, op;
  py::dict options;
};

struct PipelineCall {
  py::object metric;     // (n, 6), or
  std::string analytic;  // an analytic metric's name
  std::vector<StageSpec> cycle, polish, repair;
  py::dict rules;  // max_cycles, min_change, min_conformity_gain, near_unit_conformity, quality_passes, ...
  std::string concurrency;
  int threads = 0;
  py::object on_cycle;
};

// The adapted copy and its report, as adapt() returns them.
py::tuple run_pipeline(const PyMesh& m, const PipelineCall& call);

}  // namespace metrica::python
