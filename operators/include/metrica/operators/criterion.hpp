// Criteria: what makes one configuration of tets better than another
// (seed, section 3.1). Every operation takes one as a template parameter.
//
// The scored protocol, which every operation understands: a criterion is
// the smallest of a per-tet score, to maximise, and
//
//   static double tet_score<S>(mesh, tet vertices);              at the mesh's points
//   static double tet_score_at<S>(mesh, tet vertices, points);   with moved points
//   static double score_in(points, metric);   in a given metric (a tet
//                                   with a new vertex, its metric known)
//   static double tet_score_of<S>(mesh, live tet id);            may be cached
//   static double bar(double reference);   a candidate's smallest score must exceed it
//
// and states its traits as static constexpr bool members (CriterionTraits:
// false when absent): measures_shape (its score orders tets as the mean
// ratio does, so the shape floor is implied), indifferent (it never
// refuses: no score need be computed), score_is_mean_ratio_cubed (a new
// tet's score gives the quality cache its mean ratio);
//
// lets an operation score the old configuration once, reuse a tet's score
// across candidates and stop scoring a candidate as soon as it cannot win.
//
//   MinQuality       the smallest mean ratio grows (by a relative margin;
//                    scored as Q^3, which orders tets as Q does);
//   MaxMinEdgeWeight the smallest Laplacian edge weight grows (Barth;
//                    Marcum & Alauzet's inner-product form, edge_weight.hpp);
//   ShapeOnly        no preference: only the shape floor decides (the
//                    default of the length-driven operations: split,
//                    centroid insertion, collapse).
//
// A flip may also take a configuration criterion that is no score,
//
//   template <MetricSpace S>
//   static bool prefers(const Mesh&, old tets, new tets);
//
//   MetricDelaunay<P>  the old configuration violates the anisotropic
//                    empty-sphere criterion of eqs. (3)-(4) across one of its
//                    inner faces and the new one across none, the insphere
//                    signs decided by the Precision P (the only sign in
//                    the adaptation that is not a tet's orientation, which
//                    positive_tet decides the same under every precision).
//
// An operation applies its criterion together with a shape floor through
// one object, Acceptance (acceptance.hpp).
#pragma once

#include <metrica/metrics/space.hpp>
#include <metrica/metrics/unit_band.hpp>
#include <metrica/policy_list.hpp>
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
concept ScoredCriterion = requires(const Mesh& mesh, const TetVertices& tet, const TetPoints& points, TetId id) {
  { C::name } -> std::convertible_to<std::string_view>;
  { C::template tet_score<Isotropic>(mesh, tet) } -> std::same_as<double>;
  { C::template tet_score_at<Isotropic>(mesh, tet, points) } -> std::same_as<double>;
  { C::template tet_score_of<Isotropic>(mesh, id) } -> std::same_as<double>;
  { C::score_in(points, Sym6{}) } -> std::same_as<double>;
  { C::bar(0.0) } -> std::same_as<double>;
};

// A criterion that compares whole configurations (flips only).
template <class C>
concept ConfigurationCriterion = requires(const Mesh& mesh, std::span<const TetVertices> tets) {
  { C::template prefers<Isotropic>(mesh, tets, tets) } -> std::same_as<bool>;
};

template <class C>
concept Criterion = ScoredCriterion<C> || ConfigurationCriterion<C>;

// The traits a criterion states (criterion.hpp's header), false when it
// does not state them.
template <class C>
struct CriterionTraits {
  static constexpr bool measures_shape = requires { requires static_cast<bool>(C::measures_shape); };
  static constexpr bool indifferent = requires { requires static_cast<bool>(C::indifferent); };
  static constexpr bool score_is_mean_ratio_cubed = requires {
    requires static_cast<bool>(C::score_is_mean_ratio_cubed);
  };
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
  static constexpr std::string_view name = "min-quality";
  static constexpr bool measures_shape = true;
  // The score is Q^3: the same order and the same worst tet as Q, without
  // a cube root per tet (most of them on the candidate tets of edge
  // removals). A relative margin m on Q is about 3m on Q^3.
  template <MetricSpace S>
  static double tet_score(const Mesh& mesh, const TetVertices& t) {
    return S::mean_ratio_cubed(mesh, t);
  }
  static double score_in(const TetPoints& p, const Sym6& m) { return metrica::mean_ratio_cubed(p, m); }
  template <MetricSpace S>
  static double tet_score_at(const Mesh& mesh, const TetVertices& t, const TetPoints& p) {
    return score_in(p, S::tet_metric(mesh, t));
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh& mesh, TetId t) {
    const double q = cached_mean_ratio<S>(mesh, t);
    return q * q * q;
  }
  static double bar(double reference) { return improvement_bar(reference, 3.0 * kQualityMargin); }
  // The score of a new tet is its Q^3: the quality cache takes its cube root.
  static constexpr bool score_is_mean_ratio_cubed = true;
};

struct MaxMinEdgeWeight {
  static constexpr std::string_view name = "edge-weight";
  static double score_in(const TetPoints& p, const Sym6& m) { return min_edge_weight(p, m); }
  template <MetricSpace S>
  static double tet_score_at(const Mesh& mesh, const TetVertices& t, const TetPoints& p) {
    return score_in(p, S::tet_metric(mesh, t));
  }
  template <MetricSpace S>
  static double tet_score(const Mesh& mesh, const TetVertices& t) {
    return tet_score_at<S>(mesh, t, detail::tet_points(mesh, t));
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh& mesh, TetId t) {
    return tet_score<S>(mesh, mesh.tet(t));
  }
  static double bar(double reference) { return reference + kQualityMargin * std::abs(reference); }
};

struct ShapeOnly {
  static constexpr std::string_view name = "shape-only";
  static constexpr bool indifferent = true;
  template <MetricSpace S>
  static double tet_score(const Mesh&, const TetVertices&) {
    return 0.0;
  }
  template <MetricSpace S>
  static double tet_score_at(const Mesh&, const TetVertices&, const TetPoints&) {
    return 0.0;
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh&, TetId) {
    return 0.0;
  }
  static double score_in(const TetPoints&, const Sym6&) { return 0.0; }
  static double bar(double) { return -std::numeric_limits<double>::infinity(); }
};

static_assert(ScoredCriterion<MinQuality> && ScoredCriterion<MaxMinEdgeWeight> && ScoredCriterion<ShapeOnly>);
static_assert(CriterionTraits<MinQuality>::measures_shape && CriterionTraits<MinQuality>::score_is_mean_ratio_cubed &&
              CriterionTraits<ShapeOnly>::indifferent && !CriterionTraits<MaxMinEdgeWeight>::measures_shape);

template <Precision P = Precisions::at<0>>
struct MetricDelaunay {
  using Predicates = P;
  static constexpr std::string_view name = "metric-delaunay";
  // True when some pair of tets of `tets` sharing a face has the apex of
  // one inside the other's circumsphere in the metric (eq. (4)).
  template <MetricSpace S>
  static bool violated(const Mesh& mesh, std::span<const TetVertices> tets) {
    for (std::size_t i = 0; i < tets.size(); ++i)
      for (std::size_t j = 0; j < tets.size(); ++j) {
        if (i == j) continue;
        // The apex of j opposite a face shared with i.
        int shared = 0;
        VertexId apex = kNoId;
        for (VertexId v : tets[j]) {
          if (local_index(tets[i], v) >= 0)
            ++shared;
          else
            apex = v;
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
  template <MetricSpace S>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return violated<S>(mesh, old_tets) && !violated<S>(mesh, new_tets);
  }
};

// The criteria a flip pass takes, by the names a user gives them (the
// Python pipeline's `criterion`).
using FlipCriteria = PolicyList<MinQuality, MetricDelaunay<>, MaxMinEdgeWeight>;

static_assert(Criterion<MetricDelaunay<>> && Criterion<MinQuality>);

}  // namespace metrica
