// Criteria that decide whether a reconnection replaces one set of tets by
// another (seed, section 3.1). Each is a policy with one static function
//
//   template <MetricSpace S, Precision P>
//   static bool prefers(const Mesh&, old tets, new tets);
//
// true when the new configuration is better. Both configurations cover
// the same region and are positively oriented (the operator checked).
//
// A criterion that is a score to maximise (MinQuality, MaxMinEdgeWeight)
// also offers the ScoredCriterion interface, so an operator that compares
// several candidates with one reference scores the reference once and
// stops scoring a candidate as soon as it cannot win:
//
//   static double score(mesh, tets);           // of new tets (vertices)
//   static double score_of(mesh, tet ids);     // of live tets (may be cached)
//   static double score_beating(mesh, tets, reference);  // -inf if it does not
//
//   MinQuality       the smallest mean ratio grows (by a relative margin);
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

namespace metrica {

template <class C>
concept ScoredCriterion = requires(const Mesh& mesh, std::span<const TetVertices> tets,
                                   std::span<const TetId> ids) {
  { C::template score<Isotropic>(mesh, tets) } -> std::same_as<double>;
  { C::template score_of<Isotropic>(mesh, ids) } -> std::same_as<double>;
  { C::template score_beating<Isotropic>(mesh, tets, 0.0) } -> std::same_as<double>;
};

struct MinQuality {
  static constexpr std::string_view name = "quality";
  template <MetricSpace S>
  static double score(const Mesh& mesh, std::span<const TetVertices> tets) {
    return min_mean_ratio<S>(mesh, tets);
  }
  template <MetricSpace S>
  static double score_of(const Mesh& mesh, std::span<const TetId> ids) {
    double q = std::numeric_limits<double>::infinity();
    for (TetId t : ids) q = std::min(q, cached_mean_ratio<S>(mesh, t));
    return q;
  }
  template <MetricSpace S>
  static double score_beating(const Mesh& mesh, std::span<const TetVertices> tets, double reference) {
    const double bar = improvement_bar(reference);
    const double q = min_mean_ratio_above<S>(mesh, tets, bar);
    return q > bar ? q : -std::numeric_limits<double>::infinity();
  }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return improves_min_quality(min_mean_ratio<S>(mesh, old_tets), min_mean_ratio<S>(mesh, new_tets));
  }
};

struct MaxMinEdgeWeight {
  static constexpr std::string_view name = "edge-weight";
  template <MetricSpace S>
  static double min_weight(const Mesh& mesh, std::span<const TetVertices> tets,
                           double floor = -std::numeric_limits<double>::infinity()) {
    double w = std::numeric_limits<double>::infinity();
    for (const auto& t : tets) {
      w = std::min(w, min_edge_weight(detail::tet_points(mesh, t), S::tet_metric(mesh, t)));
      if (w <= floor) break;
    }
    return w;
  }
  template <MetricSpace S>
  static double score(const Mesh& mesh, std::span<const TetVertices> tets) {
    return min_weight<S>(mesh, tets);
  }
  template <MetricSpace S>
  static double score_of(const Mesh& mesh, std::span<const TetId> ids) {
    double w = std::numeric_limits<double>::infinity();
    for (TetId t : ids)
      w = std::min(w, min_edge_weight(detail::tet_points(mesh, mesh.tet(t)), S::tet_metric(mesh, mesh.tet(t))));
    return w;
  }
  template <MetricSpace S>
  static double score_beating(const Mesh& mesh, std::span<const TetVertices> tets, double reference) {
    const double bar = reference + kQualityMargin * std::abs(reference);
    const double w = min_weight<S>(mesh, tets, bar);
    return w > bar ? w : -std::numeric_limits<double>::infinity();
  }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    const double before = min_weight<S>(mesh, old_tets), after = min_weight<S>(mesh, new_tets);
    return after > before + kQualityMargin * std::abs(before);
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
