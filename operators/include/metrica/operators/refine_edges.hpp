// Point creation by edges: every edge longer than max_length (sqrt 2 by
// default) in the metric is split at its metric midpoint, longest first.
// Proximity filter: a new point closer than min_new_distance (in the
// metric) to a point created earlier in the same pass and joined to it by
// an edge waits for the next pass. Each split locks the vertices of its
// shell, the unit of work a thread owns under Speculative.
#pragma once

#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/boundary_placement.hpp>
#include <metrica/operators/edge_queue.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/pass_scope.hpp>
#include <metrica/operators/split_edge.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace metrica {

struct RefineOptions {
  double max_length = kUnitBand.hi;
  double min_new_distance = kUnitBand.lo;
  double shape_floor = ShapeFloors::split;
  // The metric of new vertices; only edges with an end whose ball changed
  // since scope.changed_since (the quality phase's repair works near its
  // poor tets only); the list from scope.known where it can.
  PassScope scope{};
};

// The parameter t in [0,1] of the point of ab at equal metric distance from
// a and b when the length grows geometrically from la (at a) to lb (at b),
// as the UGAWG length assumes: la ((lb/la)^t - 1) / ln(lb/la) is half of
// the total.
inline double metric_midpoint(double la, double lb) {
  const double r = lb / la;
  if (std::abs(r - 1.0) < 1e-6) return 0.5;
  return std::log(0.5 * (r + 1.0)) / std::log(r);
}

struct EdgeSplitPlan {
  Point p;
  VertexMetric metric;
  GeoParam geo;  // on the model (a boundary edge under a CAD Geometry)
};

// A new vertex on edge ab (its shell held) at a + t (b - a), `straight`:
// placed by the Geometry (boundary_placement.hpp), refused when
// `too_close(p)`, when a tet of the split would not be positive (P), or by
// `accept`; its metric from `options.scope.metric` or interpolated
// with the weights (1 - t, t). The decision of an edge split and of a
// centroid candidate moved onto a ridge.
template <MetricSpace S, class Criterion, Geometry G, class TooClose>
Decision<EdgeSplitPlan> decide_edge_point(const Mesh& mesh, const Shell& shell, VertexId a, VertexId b, double t,
                                          const Point& straight, const RefineOptions& options,
                                          const Acceptance<S, Criterion>& accept, const G& geometry,
                                          TooClose&& too_close) {
  // Required edges and, while the surface is kept, surface edges stay whole.
  if (mesh.is_required_edge(a, b)) return Refusal::not_applicable;
  if (mesh.keeps_surface() && (!shell.closed || edge_surface(mesh, shell, a, b) != 0)) return Refusal::not_applicable;
  const BoundaryPoint at = place_boundary_vertex(geometry, edge_vertex_param(geometry, mesh, shell, a, b, t), straight,
                                                 [&](const Point& q) { return split_is_valid(mesh, shell, a, b, q); });
  if (too_close(at.p)) return Refusal::rejected;
  // On an internal surface (a closed shell) the vertex goes on the model or
  // the split waits: no later pass may move it there (both sides hold it),
  // nor collapse it away as the last resort does on the outer boundary.
  if (shell.closed && at.geo.valid() && at.p != geometry.point(at.geo)) return Refusal::rejected;
  if (!split_is_valid(mesh, shell, a, b, at.p)) return Refusal::rejected;
  const std::array<VertexId, 2> ends{a, b};
  const std::array<double, 2> w{1.0 - t, t};
  const VertexMetric m = new_vertex_metric<S>(mesh, options.scope.metric, ends, w, at.p);
  if (!split_accepted(mesh, shell, a, b, at.p, m, accept)) return Refusal::rejected;
  return EdgeSplitPlan{at.p, m, at.geo};
}

struct EdgeSplitScratch : ScratchGeneration {
  TetList ball;  // the walk to the shell
  Shell shell;
  VertexList cavity;  // the shell's vertices, each once
};

// The split of a long edge at its metric midpoint, as an operation. Its
// criterion (ShapeOnly: none) and shape floor (0: none) may refuse splits
// that make poor tets. On a boundary edge the Geometry places the new
// vertex (boundary_placement.hpp).
template <MetricSpace S, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
struct EdgeSplit {
  using Item = EdgeCandidate;
  using Scratch = EdgeSplitScratch;
  using Plan = EdgeSplitPlan;
  static constexpr std::string_view name = "split";
  RefineOptions options;
  // Vertices stamped with this epoch or later were created by this pass.
  Mesh::Epoch pass_epoch = 0;
  G geometry{};

  Acceptance<S, Criterion> acceptance() const { return Acceptance<S, Criterion>(options.shape_floor); }
  // A split of a shell of n tets (5 on average) makes n new ones; the
  // proximity filter defers about half of the candidates. More comes
  // between rounds when needed.
  PassRoom room() const { return {.vertices_per_item = 0.6, .tets_per_item = 3.5}; }
  Found seed(const Mesh&, const Item& c, Scratch&, VertexList& hold) const {
    hold.emplace_back(c.a);
    hold.emplace_back(c.b);
    return Found::cavity;
  }
  Found find(const Mesh& mesh, const Item& c, Scratch& x, VertexList& hold) const {
    if (!find_edge_shell(mesh, c.a, c.b, x.ball, x.shell)) return Found::gone;
    x.cavity.clear();
    append_shell_vertices(mesh, c.a, c.b, x.shell, x.cavity);
    hold.insert(hold.end(), x.cavity.begin(), x.cavity.end());
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, const Item& c, Scratch& x) const {
    const Eigen::Vector3d e = mesh.point(c.b) - mesh.point(c.a);
    const auto& ma = S::vertex_metric(mesh, c.a);
    const auto& mb = S::vertex_metric(mesh, c.b);
    const double t = metric_midpoint(std::sqrt(metric_norm2(ma, e)), std::sqrt(metric_norm2(mb, e)));
    // Too close to a point of this pass: refused (the next pass lists the
    // edge again).
    auto too_close = [&](const Point& p) {
      for (VertexId v : x.cavity) {
        if (mesh.vertex_stamp(v) < pass_epoch) continue;
        const auto& mv = S::vertex_metric(mesh, v);
        if (std::sqrt(metric_norm2(mv, p - mesh.point(v))) < options.min_new_distance) return true;
      }
      return false;
    };
    return decide_edge_point<S>(mesh, x.shell, c.a, c.b, t, Point(mesh.point(c.a) + t * e), options, acceptance(),
                                geometry, too_close);
  }
  void apply(Mesh& mesh, const Item& c, const Plan& plan, Scratch& x) const {
    const VertexId n = split_edge(mesh, x.shell, c.a, c.b, plan.p, plan.metric);
    if (plan.geo.valid()) mesh.set_geo_param(n, plan.geo);
  }
  void preview(const Mesh& mesh, const Item& c, const Plan& plan, const Scratch& x, PlannedTets& out) const {
    preview_split(mesh, x.shell, c.a, c.b, plan.p, out);
  }
};

template <MetricSpace S, Concurrency C, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
OperatorStats refine_edges(Mesh& mesh, const RefineOptions& o = {}, const G& geometry = {}) {
  Stopwatch clock;
  const auto todo =
      edges_beyond<S, C>(mesh, o.max_length, EdgeOrder::longest_first, o.scope.changed_since, o.scope.known);
  const EdgeSplit<S, Criterion, G> split{o, mesh.next_epoch(), geometry};
  OperatorStats stats = run_pass<C>(mesh, split, todo);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
