// Criteria that decide whether a reconnection replaces one set of tets by
// another (seed, section 3.1). Each is a policy with one static function
//
//   template <MetricSpace S, Precision P>
//   static bool prefers(const Mesh&, old tets, new tets);
//
// true when the new configuration is better. Both configurations cover
// the same region and are positively oriented (the operator checked).
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

struct MinQuality {
  static constexpr std::string_view name = "quality";
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    return improves_min_quality(min_mean_ratio<S>(mesh, old_tets), min_mean_ratio<S>(mesh, new_tets));
  }
};

struct MaxMinEdgeWeight {
  static constexpr std::string_view name = "edge-weight";
  template <MetricSpace S>
  static double min_weight(const Mesh& mesh, std::span<const TetVertices> tets) {
    double w = std::numeric_limits<double>::infinity();
    for (const auto& t : tets) w = std::min(w, min_edge_weight(detail::tet_points(mesh, t), S::tet_metric(mesh, t)));
    return w;
  }
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh& mesh, std::span<const TetVertices> old_tets, std::span<const TetVertices> new_tets) {
    const double before = min_weight<S>(mesh, old_tets), after = min_weight<S>(mesh, new_tets);
    return after > before + kQualityMargin * std::abs(before);
  }
};

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
