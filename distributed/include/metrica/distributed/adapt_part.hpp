// The adaptation of one rank's part: the part becomes a Mesh whose faces
// shared with other parts are required boundary faces (a reserved surface
// id, kept exactly as the input's RequiredTriangles are: their vertices
// and edges neither move, split nor go), the standard pipeline adapts the
// rest, and the result goes back to global ids. The kept faces' vertices
// keep theirs (a vertex attribute of the part's mesh, which they carry
// through the adaptation); every other vertex gets a new one.
#pragma once

#include <metrica/distributed/comm.hpp>
#include <metrica/distributed/part.hpp>
#include <metrica/geometry/cad_model.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

#include <algorithm>

namespace metrica::distributed {

// The surface id of the faces between parts while a part is adapted: the
// largest id a mesh may have, which inputs may not use under mpirun.
inline constexpr SurfaceId kPartFaceId = kMaxSurfaceId - 1;

// Where a part's rounds differ from the single process on purpose
// (docs/distributed.md, "Two settings differ on purpose"): a part's
// poorest tets lie against the faces it keeps and the next round adapts
// them again, so more flip sweeps a quality pass and cycles down to a
// smaller gain in the unit band take fewer rounds. The settings given are
// raised to these, never lowered.
//
// And in every round, the first included: beside a kept face whose edges
// are long in the metric the round splits the free edges toward its
// vertices again and again, and with no floor (the single process's
// default) the children thin to needles (mean ratio 1e-11, flat to the
// orientation test's rounding) that no later round can split or flip: a
// split may not make a tet below min_split_floor unless its shell had a
// worse one.
struct PartRoundRules {
  int min_polish_sweeps = 4;
  double max_min_conformity_gain = 0.005;
  double min_split_floor = 0.01;
  AdaptOptions applied_to(AdaptOptions o) const {
    o = applied_to_first(o);
    o.polish_sweeps = std::max(o.polish_sweeps, min_polish_sweeps);
    o.min_conformity_gain = std::min(o.min_conformity_gain, max_min_conformity_gain);
    return o;
  }
  // What the first round takes of these.
  AdaptOptions applied_to_first(AdaptOptions o) const {
    o.refine.shape_floor = std::max(o.refine.shape_floor, min_split_floor);
    return o;
  }
};

struct PartAdaptSettings {
  AdaptOptions options;
  PolicyChoice policies;
  // The analytic metric (new vertices take it); else the metric file's
  // field on the input mesh (new and moved vertices take it there); none:
  // interpolated from the part's metrics.
  const MetricFunction* exact = nullptr;
  const BackgroundMetric* background = nullptr;
  // The id of boundary faces no input triangle covers (the same on all ranks).
  SurfaceId default_surface_id = 1;
  // The CAD model the boundary lies on (Part::geo); none: the input's facets.
  const CadModel* model = nullptr;
  // --keep-surface: the boundary and internal surfaces stay as they are.
  bool keep_surface = false;
  // Undo the part's round when it leaves a tet poorer than the poorest it
  // was given and below kPoorAtKeptFace (the last round on a mesh adapted
  // before).
  bool keep_worst = false;
};

// The quality of some tets in their metric: edges (once per piece they
// are measured in), those in [1/sqrt 2, sqrt 2], tets, worst and summed
// mean ratios.
struct QualityTally {
  std::int64_t edges = 0, edges_in_range = 0, tets = 0;
  double min_quality = 1, sum_quality = 0;
};

struct PartAdaptResult {
  double volume_before = 0, volume_after = 0;
  double seconds = 0;
  std::int64_t kept_out = 0;  // tets around pinches, left for a later round (pinches.hpp)
  std::int64_t adapted = 0;   // tets given to the adaptation
  // The vertices the round left unfinished (the next round's focus):
  // those of the tets kept out at pinches, of the tets of mean ratio below
  // kPoorTet, and those of the kept faces that touch an edge of length
  // outside [kShortEdge, kLongEdge] or a tet below kPoorAtKeptFace (the
  // adaptation cannot flip or move a kept face: what it leaves there the
  // next round, with the face inside a part, does better). A kept face in
  // a part adapted already (a later cut through finished mesh) leaves
  // little to do; a coarse one leaves long edges and poor tets.
  std::vector<GlobalId> kept_vertices;
  // The vertices of the adapted tets below kPoorAtKeptFace and those left
  // off the model: what keeps an adaptation from ending (its last rounds
  // adapt only around them).
  std::vector<GlobalId> poor_vertices;
  // Every vertex the round held as it was (sorted, once each): those of
  // the faces it kept and of the tets it kept out at pinches.
  std::vector<GlobalId> held;
  QualityTally quality;  // of the adapted tets
  // Boundary vertices farther than kOnModel from their entity (with a
  // model), among the unfinished ones.
  std::int64_t off_model = 0;
  // keep_worst undid the round on this part: its tets are as they came.
  bool undone = false;
};

// How near its entity a boundary vertex must be (check --geometry's default).
inline constexpr double kOnModel = 1e-8;

inline constexpr double kShortEdge = 0.5, kLongEdge = 2.0, kPoorTet = 0.3, kPoorAtKeptFace = 0.5;

// Adapts the part in place (the tets Part::focus flags, all when it is
// empty); on a model new boundary vertices go on it. `next_id` (the same on every rank) is the
// first unused global id, advanced past the new vertices of all ranks.
// Throws (on every rank) when one part's adaptation failed or left an
// invalid mesh.
PartAdaptResult adapt_part(const Comm& comm, Part& part, const PartAdaptSettings& settings, GlobalId& next_id);

// The quality of the whole part in the settings' space and metric,
// measured on pieces of at most kQualityPieceTets tets at a time (a
// Mesh of the whole part would double a rank's memory at the end); an
// edge on two pieces counts twice, as one between two parts does.
inline constexpr std::size_t kQualityPieceTets = 250'000;
QualityTally part_quality(const Part& part, const PartAdaptSettings& settings);

}  // namespace metrica::distributed
