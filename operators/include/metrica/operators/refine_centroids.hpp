// Point creation by centroids (seed, section 3.2, and its figure of
// encroachment rules): every tet with an edge longer than max_length
// proposes its centroid. Near the boundary the candidate moves, as in
// constrained Delaunay refinement (Shewchuk 1998), but measured in the
// metric:
//
//   - if it encroaches a boundary face of its tet (lies inside the face's
//     diametral sphere: closer to the face's circumcentre than the
//     circumradius), it becomes that face's centroid;
//   - if the candidate then encroaches a ridge edge of its tet (closer to
//     the edge's midpoint than half its length), it becomes the edge's
//     metric midpoint.
//
// A candidate closer than min_new_distance (in the metric of each vertex)
// to a vertex of its tet, or to the candidate of a neighbouring tet, is
// dropped; one candidate per edge. Candidates are stored with their
// containing element (the tet, its boundary face, or its ridge edge), so
// insertion needs no point location: the tet splits 1 -> 4, the face
// 1 -> 3, the edge's shell in two. Two passes: all candidates are made
// from the unchanged mesh (pure reads, on one thread: the proximity test
// against the neighbours' candidates depends on their order), then
// inserted, in parallel under Speculative; a candidate whose tet an
// earlier insertion changed waits for the next cycle (Mesh epochs say
// which).
#pragma once

#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/boundary_placement.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/operators/split_cell.hpp>
#include <metrica/operators/split_edge.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <vector>

namespace metrica {

// Where a candidate lies, so that it is inserted without a search.
struct PointCandidate {
  Point p;
  TetId tet = kNoId;
  int face = -1;                  // >= 0: on this boundary face of tet
  VertexId a = kNoId, b = kNoId;  // != kNoId: on ridge edge ab (of tet)
  double t = 0.5;                 // position on ab (a + t (b - a))
};

namespace detail {
// Squared distance of p to q in metric m.
inline double metric_distance2(const Sym6& m, const Point& p, const Point& q) { return metric_norm2(m, p - q); }

// Does p lie strictly inside the diametral sphere of triangle (x0, x1, x2)
// measured in metric m? Computed after mapping by L (M = L^T L).
inline bool encroaches_face(const Matrix3& l, const Point& p, const Point& x0, const Point& x1, const Point& x2) {
  const Eigen::Vector3d a = l * x0, u = l * x1 - a, v = l * x2 - a;
  const Eigen::Vector3d w = u.cross(v);
  const double w2 = w.squaredNorm();
  if (!(w2 > 0.0)) return false;
  const Eigen::Vector3d to_centre = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w2);
  const Eigen::Vector3d centre = a + to_centre;
  return (l * p - centre).squaredNorm() < to_centre.squaredNorm();
}
}  // namespace detail

// The candidates of the centroid rule, from the mesh as it is (reads only).
template <MetricSpace S>
std::vector<PointCandidate> centroid_candidates(const Mesh& mesh, const RefineOptions& o,
                                                std::vector<std::uint32_t>& candidate_of_tet) {
  std::vector<PointCandidate> out;
  candidate_of_tet.assign(mesh.tet_capacity(), kNoId);
  std::unordered_set<std::uint64_t> edges_taken;  // ridge edges with a candidate
  const double min2 = o.min_new_distance * o.min_new_distance;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    bool long_edge = false;
    for (const auto& e : kEdgeVertex) long_edge = long_edge || S::edge_length(mesh, v[e[0]], v[e[1]]) > o.max_length;
    if (!long_edge) continue;
    PointCandidate c;
    c.tet = t;
    c.p = 0.25 * (mesh.point(v[0]) + mesh.point(v[1]) + mesh.point(v[2]) + mesh.point(v[3]));
    // Encroached boundary face: its centroid instead.
    for (int f = 0; f < 4 && c.face < 0; ++f) {
      if (mesh.neighbour(t, f).valid()) continue;
      const auto fv = face_vertices(v, f);
      const std::array<double, 3> w{1.0 / 3, 1.0 / 3, 1.0 / 3};
      const Matrix3 l = S::factor(S::metric_at(mesh, std::span<const VertexId>(fv), w));
      if (detail::encroaches_face(l, c.p, mesh.point(fv[0]), mesh.point(fv[1]), mesh.point(fv[2]))) {
        c.face = f;
        c.p = (mesh.point(fv[0]) + mesh.point(fv[1]) + mesh.point(fv[2])) / 3.0;
      }
    }
    // Encroached ridge edge (of the face when on one): its metric midpoint.
    for (const auto& e : kEdgeVertex) {
      const VertexId a = v[e[0]], b = v[e[1]];
      if (c.face >= 0 && (v[c.face] == a || v[c.face] == b)) continue;  // not an edge of the face
      if (!mesh.is_ridge(a, b)) continue;
      const std::array<VertexId, 2> ends{a, b};
      const std::array<double, 2> half{0.5, 0.5};
      const Sym6 m = S::metric_at(mesh, ends, half);
      const Point mid = 0.5 * (mesh.point(a) + mesh.point(b));
      if (4.0 * detail::metric_distance2(m, c.p, mid) >= detail::metric_distance2(m, mesh.point(a), mesh.point(b)))
        continue;
      const Eigen::Vector3d d = mesh.point(b) - mesh.point(a);
      c.a = a;
      c.b = b;
      c.t = metric_midpoint(std::sqrt(metric_norm2(S::vertex_metric(mesh, a), d)),
                            std::sqrt(metric_norm2(S::vertex_metric(mesh, b), d)));
      c.p = mesh.point(a) + c.t * d;
      c.face = -1;
      break;
    }
    // Proximity: the tet's vertices, the neighbours' candidates, one per edge.
    bool close = false;
    auto near_vertex = [&](VertexId x) {
      return x != c.a && x != c.b && detail::metric_distance2(S::vertex_metric(mesh, x), c.p, mesh.point(x)) < min2;
    };
    for (int f = 0; f < 4 && !close; ++f) {
      close = near_vertex(v[f]);
      // and the apex of the neighbour across each face
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid()) close = close || near_vertex(mesh.tet(n.tet())[n.face()]);
    }
    for (int f = 0; f < 4 && !close; ++f) {
      const FaceRef n = mesh.neighbour(t, f);
      if (!n.valid() || candidate_of_tet[n.tet()] == kNoId) continue;
      const PointCandidate& other = out[candidate_of_tet[n.tet()]];
      close = detail::metric_distance2(S::tet_metric(mesh, v), c.p, other.p) < min2;
    }
    if (c.a != kNoId) {
      const std::uint64_t key = edge_key(c.a, c.b);
      close = close || edges_taken.count(key) != 0;
      if (!close) edges_taken.insert(key);
    }
    if (close) continue;
    candidate_of_tet[t] = static_cast<std::uint32_t>(out.size());
    out.emplace_back(c);
  }
  return out;
}

struct CentroidScratch : ScratchGeneration {
  CellSplitScratch cell;
  Shell shell;
  TetVertices seen{};  // the candidate's tet as the seed step read it
};

struct CentroidPlan {
  VertexMetric metric;
  Point p;       // the candidate's point, or its place on the model
  GeoParam geo;  // on the model (a boundary candidate under a CAD Geometry)
};

// The insertion of a candidate of the centroid rule, as an operation: its
// tet must be as it was when the candidate was made (Mesh epochs).
template <MetricSpace S, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
struct CentroidInsertion {
  using Item = PointCandidate;
  using Scratch = CentroidScratch;
  using Plan = CentroidPlan;
  static constexpr std::string_view name = "centroids";
  RefineOptions options;
  Mesh::Epoch start = 0;  // when the candidates were made
  G geometry{};

  Acceptance<S, Criterion> acceptance() const { return Acceptance<S, Criterion>(options.shape_floor); }
  PassRoom room() const { return {.vertices_per_item = 1.0, .tets_per_item = 4.0}; }
  Found seed(const Mesh& mesh, const Item& c, Scratch& x, VertexList& hold) const {
    x.seen = mesh.peek_tet(c.tet);
    // A tet removed or changed in this pass is gone as listed: the next
    // pass lists the tets that replaced it.
    if (std::find(x.seen.begin(), x.seen.end(), kNoId) != x.seen.end()) return Found::gone;
    hold.insert(hold.end(), x.seen.begin(), x.seen.end());
    return Found::cavity;
  }
  Found find(const Mesh& mesh, const Item& c, Scratch& x, VertexList& hold) const {
    if (mesh.tet(c.tet) != x.seen || mesh.changed_since(c.tet, start)) return Found::gone;
    if (c.a != kNoId) {
      edge_shell_from(mesh, c.a, c.b, c.tet, x.shell);
      append_vertices(mesh, x.shell.tets, hold);
    }
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, const Item& c, Scratch& x) const {
    const TetVertices& v = x.seen;
    if (c.a != kNoId) {
      const auto d = decide_edge_point<S>(mesh, x.shell, c.a, c.b, c.t, c.p, options, acceptance(), geometry,
                                          [](const Point&) { return false; });
      if (!d) return d.why();
      return Plan{d.plan().metric, d.plan().p, d.plan().geo};
    }
    if (c.face >= 0 && (mesh.neighbour(c.tet, c.face).valid() || mesh.surface_id(c.tet, c.face) <= 0))
      return Refusal::not_applicable;
    // Nothing goes inside a required triangle (its edges are all required)
    // or on a kept surface.
    if (c.face >= 0) {
      if (mesh.keeps_surface()) return Refusal::not_applicable;
      const auto f = face_vertices(v, c.face);
      if (mesh.is_required_edge(f[0], f[1]) && mesh.is_required_edge(f[1], f[2]) && mesh.is_required_edge(f[2], f[0]))
        return Refusal::not_applicable;
    }
    std::array<VertexId, 4> ids{};
    std::array<double, 4> w{};
    std::size_t k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != c.face) ids[k++] = v[i];
    std::fill(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(k), 1.0 / static_cast<double>(k));
    const std::span<const VertexId> parents(ids.data(), k);
    const std::span<const double> weights(w.data(), k);
    const GeoParam param =
        c.face >= 0 ? geometry.boundary_vertex(mesh, parents, weights, mesh.surface_id(c.tet, c.face)) : GeoParam{};
    const BoundaryPoint at = place_boundary_vertex(
        geometry, param, c.p, [&](const Point& q) { return cell_split_is_valid(mesh, c.tet, c.face, q); });
    if (!cell_split_is_valid(mesh, c.tet, c.face, at.p)) return Refusal::rejected;
    const VertexMetric m = new_vertex_metric<S>(mesh, options.scope.metric, parents, weights, at.p);
    if (!cell_split_accepted(mesh, c.tet, c.face, at.p, m, acceptance())) return Refusal::rejected;
    return Plan{m, at.p, at.geo};
  }
  void apply(Mesh& mesh, const Item& c, const Plan& plan, Scratch& x) const {
    const VertexId n = c.a != kNoId ? split_edge(mesh, x.shell, c.a, c.b, plan.p, plan.metric)
                                    : split_cell(mesh, c.tet, c.face, plan.p, plan.metric, x.cell);
    if (plan.geo.valid()) mesh.set_geo_param(n, plan.geo);
  }
  void preview(const Mesh& mesh, const Item& c, const Plan& plan, const Scratch& x, PlannedTets& out) const {
    if (c.a != kNoId)
      preview_split(mesh, x.shell, c.a, c.b, plan.p, out);
    else
      preview_cell_split(mesh, c.tet, c.face, plan.p, out);
  }
};

template <MetricSpace S, Concurrency C, class Criterion = ShapeOnly, Geometry G = ModelOrFacets>
OperatorStats refine_centroids(Mesh& mesh, const RefineOptions& o = {}, const G& geometry = {}) {
  Stopwatch clock;
  std::vector<std::uint32_t> candidate_of_tet;
  const Mesh::Epoch start = mesh.next_epoch();
  const auto candidates = centroid_candidates<S>(mesh, o, candidate_of_tet);
  OperatorStats stats = run_pass<C>(mesh, CentroidInsertion<S, Criterion, G>{o, start, geometry}, candidates);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
