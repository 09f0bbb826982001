// `metrica adapt` on several MPI ranks (docs/distributed.md): read in
// slices, then rounds of cut (PT-Scotch) - move - adapt with the faces
// between parts kept, each cut staying away from the faces the round
// before kept, then one .meshb written by all ranks together.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <optional>
#include <string>

namespace metrica::distributed {

struct DistributedAdapt {
  std::string input, output;
  std::string metric;    // a .sol/.solb at the input's vertices, or empty with `analytic`
  bool background = true;  // with `metric`: new and moved vertices take it on the input mesh (else from parents)
  std::string geometry;  // the CAD model the boundary lies on (every rank opens it), or empty
  std::optional<AnalyticMetric> analytic;
  MetricBounds bounds;
  AdaptOptions options;
  PolicyChoice policies;
  int iterations = 1;         // --analytic only: the metric re-evaluated between them
  int rounds = 5;             // at most this many cuts per adaptation
  int version = 0;            // libMeshb version of the output (0: chosen by size)
  std::string metric_out;     // also the metric at the output's vertices (.solb), or empty
  std::string vtu;            // also the mesh for ParaView (.vtu), or empty
  bool keep_surface = false;  // the boundary and internal surfaces stay as they are
  bool dry_run = false;       // read and check the inputs, say what would be done, adapt and write nothing
  // A run predicted to make more tets is refused before any work (0: no
  // limit); `max_tets_reason` says where the limit comes from.
  double max_tets = 0;
  std::string max_tets_reason;
  bool talk = true;  // rank 0 prints progress, and the output's quality (measured only then)
};

// Runs on every rank of comm; throws ReportedFailure (every rank) after an
// error on any, which that rank has printed.
void adapt_distributed(const Comm& comm, const DistributedAdapt& run);

}  // namespace metrica::distributed
