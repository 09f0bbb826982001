// Criteria that decide whether a reconnection replaces one set of tets by
// another (seed, section 3.1). Each is a policy with one static function
//
//   template <MetricSpace S, Precision P>
//   static bool prefers(const Mesh&, old tets, new tets);
//
// true when the new configuration is better. Both configurations cover
// the same region and are positively oriented (the operator checked).
//
// A criterion that is the smallest of a per-tet score, to maximise
// (MinQuality, MaxMinEdgeWeight), also offers the ScoredCriterion
// interface, so an operator comparing several candidates with one
// reference scores the reference once, reuses a tet's score across
// candidates, and stops scoring a candidate as soon as it cannot win:
//
//   static double tet_score<S>(mesh, tet vertices);
//   static double tet_score_of<S>(mesh, live tet id);   // may be cached
//   static double bar(double reference);   // a candidate must exceed it
//
//   MinQuality       the smallest mean ratio grows (by a relative margin;
//                    scored as Q^3, which orders tets as Q does);
//   MaxMinEdgeWeight the smallest Laplacian edge weight grows (Barth;
//                    Marcum & Alauzet's inner-product form, edge_weight.hpp);
//   MetricDelaunay   the old configuration violates the anisotropic
//                    empty-sphere criterion of eqs. (3)-(4) across one of its
//                    inner faces and the new one across none.
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/predicates/edge_weight.hpp>
#include <metrica/predicates/metric_delaunay.hpp>
#include <metrica/predicates/quality_criterion.hpp>

#include <algorithm>
#include <limits>
#include <span>
#include <string_view>
#include <type_traits>

namespace metrica {

template <class C>
concept ScoredCriterion = requires(const Mesh& mesh, const TetVertices& tet, TetId id) {
  { C::template tet_score<Isotropic>(mesh, tet) } -> std::same_as<double>;
  { C::template tet_score_of<Isotropic>(mesh, id) } -> std::same_as<double>;
  { C::bar(0.0) } -> std::same_as<double>;
};

// The smallest score of `ids` (live tets) and of `tets` (new ones); the
// latter stops at the first tet at or below `floor`.
template <class C, MetricSpace S>
double min_score_of(const Mesh& mesh, std::span<const TetId> ids) {
  double q = std::numeric_limits<double>::infinity();
  for (TetId t : ids) q = std::min(q, C::template tet_score_of<S>(mesh, t));
  return q;
}
template <class C, MetricSpace S>
double min_score(const Mesh& mesh, std::span<const TetVertices> tets,
                 double floor = -std::numeric_limits<double>::infinity()) {
  double q = std::numeric_limits<double>::infinity();
  for (const auto& t : tets) {
    q = std::min(q, C::template tet_score<S>(mesh, t));
    if (q <= floor) break;
  }
  return q;
}

struct MinQuality {
  static constexpr std::string_view name = "quality";
  // The score is Q^3: the same order and the same worst tet as Q, without
  // a cube root per tet (cbrt was 2.4% of an adaptation, most of it on the
  // candidate tets of edge removals). A relative margin m on Q is about 3m
  // on Q^3.
  template <MetricSpace S>
  static double tet_score(const Mesh& mesh, const TetVertices& t) {
    return S::mean_ratio_cubed(mesh, t);
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh& mesh, TetId t) {
    const double q = cached_mean_ratio<S>(mesh, t);
    return q * q * q;
  }
  static double bar(double reference) { return improvement_bar(reference, 3.0 * kQualityMargin); }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return improves_min_quality(min_mean_ratio<S>(mesh, old_tets), min_mean_ratio<S>(mesh, new_tets));
  }
};

// After a flip under Criterion is applied: under MinQuality the scores of
// its new tets (in the order `created` lists them) are their Q^3, so the
// quality cache gets them for a cube root each instead of a fresh mean
// ratio later (the same value up to rounding). Without a score per new
// tet (an edge removal whose ring was too large to memoise) or under
// other criteria: nothing.
template <class Criterion>
void cache_new_qualities(const Mesh& mesh, std::span<const TetId> created, std::span<const double> scores) {
  if constexpr (std::is_same_v<Criterion, MinQuality>) {
    if (scores.size() != created.size()) return;
    for (std::size_t i = 0; i < created.size(); ++i) mesh.cache_quality(created[i], std::cbrt(scores[i]));
  }
}

struct MaxMinEdgeWeight {
  static constexpr std::string_view name = "edge-weight";
  template <MetricSpace S>
  static double tet_score(const Mesh& mesh, const TetVertices& t) {
    return min_edge_weight(detail::tet_points(mesh, t), S::tet_metric(mesh, t));
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh& mesh, TetId t) {
    return tet_score<S>(mesh, mesh.tet(t));
  }
  static double bar(double reference) { return reference + kQualityMargin * std::abs(reference); }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return min_score<MaxMinEdgeWeight, S>(mesh, new_tets) > bar(min_score<MaxMinEdgeWeight, S>(mesh, old_tets));
  }
};

static_assert(ScoredCriterion<MinQuality> && ScoredCriterion<MaxMinEdgeWeight>);

struct MetricDelaunay {
  static constexpr std::string_view name = "delaunay";
  // True when some pair of tets of `tets` sharing a face has the apex of
  // one inside the other's circumsphere in the metric (eq. (4)).
  template <MetricSpace S, Precision P>
  static bool violated(const Mesh& mesh, std::span<const TetVertices> tets) {
    for (std::size_t i = 0; i < tets.size(); ++i)
      for (std::size_t j = 0; j < tets.size(); ++j) {
        if (i == j) continue;
        // The apex of j opposite a face shared with i.
        int shared = 0;
        VertexId apex = kNoId;
        for (VertexId v : tets[j]) {
          if (local_index(tets[i], v) >= 0) ++shared;
          else apex = v;
        }
        if (shared != 3) continue;
        const auto& k = tets[i];
        const std::array<Sym6, 4> mk{S::vertex_metric(mesh, k[0]), S::vertex_metric(mesh, k[1]),
                                     S::vertex_metric(mesh, k[2]), S::vertex_metric(mesh, k[3])};
        if (metric_delaunay_violated<P>(detail::tet_points(mesh, k), mesh.point(apex), mk,
                                        S::vertex_metric(mesh, apex)))
          return true;
      }
    return false;
  }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return violated<S, P>(mesh, old_tets) && !violated<S, P>(mesh, new_tets);
  }
};

}  // namespace metrica
