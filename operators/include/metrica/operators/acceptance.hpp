// Acceptance: what every operation asks before it replaces tets, stated
// once. An operation holds its Criterion (criterion.hpp) and its shape
// floor (its options' `shape_floor`, the defaults in ShapeFloors) in one
// Acceptance and asks it
//
//   replacing(mesh, old tets)   a Replacement: for each new tet, does it
//                               pass the shape floor (shape_admits) and
//                               beat the old configuration's bar under the
//                               criterion (beats; a split's child:
//                               admits_child)?
//   keeps_shape(mesh, old, new) the floor over new tets at the mesh's points
//   after_apply(mesh, created, scores)   the quality cache gets what the
//                               scores already measured
//
// The shape floor: no new tet below the floor in mean ratio unless the old
// configuration already had a worse one. Without it, metric Delaunay or
// edge-weight flips on a flat boundary made tets of Q ~ 1e-11 (positive
// for the exact predicate, a fold of the surface for the rest). A
// criterion that measures shape (MinQuality) implies it, and a floor of 0
// asks nothing (the operations check orientation themselves).
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/operators/criterion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace metrica {

// The shape floor of each operation, one default each (the options'
// `shape_floor`).
struct ShapeFloors {
  // A split refines what it is given: its tets are as good as their
  // parents allow (a floor asks beside fixed vertices only: admits_child).
  static constexpr double split = 0.0;
  // A collapse can make what later cycles cannot undo.
  static constexpr double collapse = 0.1;
  // Flips and smoothing under a criterion that does not measure shape must
  // not fold a flat boundary (tets of Q ~ 1e-11 without a floor).
  static constexpr double flip = 1e-3;
  static constexpr double smoothing = 1e-3;
  // A boundary swap and a projection follow the model: no criterion
  // decides them, and by default no floor (their new tets are checked
  // positive; the flips and smoothing around them lift what they leave).
  static constexpr double boundary_swap = 0.0;
  static constexpr double projection = 0.0;
};

template <MetricSpace S, class Criterion>
class Acceptance {
 public:
  using Traits = CriterionTraits<Criterion>;

  constexpr explicit Acceptance(double shape_floor) : floor_(shape_floor) {}
  double shape_floor() const { return floor_; }
  // Whether the floor asks anything, and whether anything is asked at all.
  bool floor_applies() const { return !Traits::measures_shape && floor_ > 0.0; }
  bool decides() const { return floor_applies() || !Traits::indifferent; }

  // One replacement of live tets `old` (and `more_old`: a collapse's
  // dragged ball) by new tets, each given with the tet whose vertices'
  // metric measures it and its points. The worst old mean ratio and the
  // criterion's bar are measured on first use.
  class Replacement {
   public:
    Replacement(const Acceptance& a, const Mesh& mesh, std::span<const TetId> old, std::span<const TetId> more_old)
        : floor_(a.floor_applies() ? a.floor_ : -std::numeric_limits<double>::infinity()),
          mesh_(mesh),
          old_(old),
          more_old_(more_old) {}

    // A new tet of mean ratio q passes the floor.
    bool shape_admits(double q) { return q >= floor_ || !(q < worst_old()); }
    bool shape_admits(const TetVertices& metric_of, const TetPoints& x) {
      return floor_ == -std::numeric_limits<double>::infinity() || shape_admits(S::mean_ratio(mesh_, metric_of, x));
    }
    // A new tet beats the old configuration under the criterion (always,
    // for an indifferent one).
    bool beats(const TetVertices& metric_of, const TetPoints& x) {
      if constexpr (Traits::indifferent) {
        return true;
      } else {
        return Criterion::template tet_score_at<S>(mesh_, metric_of, x) > bar();
      }
    }
    // A split's child of `parent` (live, not yet replaced): the criterion
    // in the metric m the child will have; the floor only beside a vertex
    // no operation moves (required, kept surface, a part's kept faces),
    // where a needle stays: elsewhere flips and smoothing lift what a
    // split leaves, and a floor would keep tets at it. The floor is
    // measured in the parent's metric, against the parent alone: a needle
    // is thin there, while a child poor only in a new vertex's much finer
    // metric is a step toward a thin layer that the next splits refine;
    // and no child thinner than its parent below the floor keeps splits
    // from going lower one after another.
    bool admits_child(TetId parent, const TetPoints& x, const Sym6& m) {
      const TetVertices& pv = mesh_.tet(parent);
      if (floor_ != -std::numeric_limits<double>::infinity() &&
          std::any_of(pv.begin(), pv.end(), [&](VertexId v) { return mesh_.is_fixed(v); })) {
        const double q = S::mean_ratio(mesh_, pv, x);
        if (q < floor_ && q < cached_mean_ratio<S>(mesh_, parent)) return false;
      }
      if constexpr (Traits::indifferent) {
        return true;
      } else {
        return Criterion::score_in(x, m) > bar();
      }
    }

    double worst_old() {
      if (std::isnan(worst_)) {
        worst_ = std::numeric_limits<double>::infinity();
        for (auto list : {old_, more_old_})
          for (TetId t : list) worst_ = std::min(worst_, cached_mean_ratio<S>(mesh_, t));
      }
      return worst_;
    }
    double bar() {
      if (std::isnan(bar_)) {
        double q = std::numeric_limits<double>::infinity();
        for (auto list : {old_, more_old_}) q = std::min(q, min_score_of<Criterion, S>(mesh_, list));
        bar_ = Criterion::bar(q);
      }
      return bar_;
    }

   private:
    double floor_;
    const Mesh& mesh_;
    std::span<const TetId> old_, more_old_;
    double worst_ = std::numeric_limits<double>::quiet_NaN();
    double bar_ = std::numeric_limits<double>::quiet_NaN();
  };

  Replacement replacing(const Mesh& mesh, std::span<const TetId> old, std::span<const TetId> more_old = {}) const {
    return Replacement(*this, mesh, old, more_old);
  }

  // The floor over `new_tets` (at the mesh's points) replacing `old`.
  bool keeps_shape(const Mesh& mesh, std::span<const TetId> old, std::span<const TetVertices> new_tets) const {
    if (!floor_applies()) return true;
    Replacement r = replacing(mesh, old);
    for (const auto& t : new_tets)
      if (!r.shape_admits(S::mean_ratio(mesh, t))) return false;
    return true;
  }

  // After the replacement is applied: when the criterion's scores are Q^3,
  // the quality cache gets the new tets' mean ratios (in the order
  // `created` lists them) for a cube root each instead of a fresh mean
  // ratio later. Without a score per new tet, or under other criteria:
  // nothing.
  static void after_apply(const Mesh& mesh, std::span<const TetId> created, std::span<const double> scores) {
    if constexpr (Traits::score_is_mean_ratio_cubed) {
      if (scores.size() != created.size()) return;
      for (std::size_t i = 0; i < created.size(); ++i) mesh.cache_quality(created[i], std::cbrt(scores[i]));
    }
  }

 private:
  double floor_;
};

}  // namespace metrica
