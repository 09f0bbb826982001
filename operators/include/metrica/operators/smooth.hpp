// Vertex smoothing (seed, section 3.4): a vertex of a poor tet moves to the
// trial position that maximises the smallest mean ratio of its ball; it
// stays where it is unless that minimum grows, and never inverts a tet.
//
// Trial positions, by class:
//   interior  along the directions to the centroids of the ball's outer
//             faces (the seed's rule), to the mean of its neighbours, and to
//             the "optimal point": the mean of the apexes of the regular
//             tets erected, in each tet's metric, on its outer faces;
//   surface   (only where its boundary faces are coplanar, so the surface
//             and the volume stay what they were) towards the midpoints of
//             the outer edges of its boundary faces, and the optimal point
//             projected into the plane;
//   ridge     (only on a straight ridge) towards its two ridge neighbours;
//   corner / required: fixed.
// A vertex of an internal surface is a surface or ridge vertex like those
// of the outer boundary: its surface faces are those of the internal
// surface (seen from both sides), and it moves within it.
// Under a Geometry on a model (CadGeometry) a boundary vertex moves on it,
// in its parameters: a surface vertex towards the midpoints of the outer
// edges of its boundary faces and towards the mean of its neighbours on
// the surface, a ridge vertex towards its two ridge neighbours along the
// curve, each trial interpolated by the Geometry and evaluated on the
// model, whatever the shape of the surface.
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/operators/acceptance.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/pass_scope.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/operators/volume_budget.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <array>
#include <atomic>
#include <vector>

namespace metrica {

struct SmoothOptions {
  // Vertices of tets with mean ratio below this are smoothed.
  double below = 0.1;
  // Boundary faces (and ridge edges) around a vertex count as flat when
  // 1 - |cos| between them is below this.
  double flat_tolerance = 1e-12;
  double shape_floor = ShapeFloors::smoothing;
  // Off a model, the budget a boundary vertex's move takes its change of
  // the domain's volume from (volume_budget.hpp): a ridge vertex moving
  // along its straight ridge drags the curved faces on either side, and
  // flat faces are flat within flat_tolerance only.
  const VolumeBudget* volume_budget = nullptr;
  // With a background, a move of a vertex whose ball's worst tet is below
  // this must also raise it in the metric sampled at the new point. The
  // check costs a tet metric per ball tet; the balls above are far from
  // the mesh's worst tets (docs/benchmarks.md, "Smoothing checked in the
  // metric sampled at the new point").
  double resample_below = 0.6;
  // The metric a moved vertex takes at its new position; only vertices
  // with a tet written since scope.changed_since (smoothing v reads only
  // v's ball; valid only when `below` is no larger than in the pass that
  // tried them).
  PassScope scope{};
};

// What the mean ratio of a ball tet needs when only v moves, as functions
// of d = p - x, v's offset from where it is (x): with f0, f1, f2 the face
// opposite v and n its inward normal, six times the volume is
// n . d + n . (x - f0), and the sum of the squared metric lengths of the
// six edges is
//   sum_i (d - e_i)^T M (d - e_i) + face_edges
//     = 3 d^T M d - 2 d . (M sum_i e_i) + (sum_i e_i^T M e_i + face_edges),
// e_i = f_i - x (all of the tet's size: no cancellation). A trial costs a
// quadratic form and two dot products per tet, not the tet's six edges,
// a determinant and an orientation test; M is the tet's metric, fixed
// while only v moves (v keeps its metric until it moves).
struct BallTerm {
  Eigen::Vector3d normal;
  double volume0 = 0.0;    // n . (x - f0): six times the volume at d = 0
  Eigen::Vector3d linear;  // M sum_i e_i
  double constant = 0.0;   // sum_i e_i^T M e_i + face_edges
  double scale = 0.0;      // the mean ratio's constant times det M
  // The cube of the mean ratio at offset d (sign kept) as a fraction:
  // numerator and denominator (the denominator > 0 but for a degenerate
  // metric, where the tet counts as flat).
  std::pair<double, double> quality3_parts(const Sym6& m, const Eigen::Vector3d& d) const {
    const double volume6 = normal.dot(d) + volume0;
    const double sum = 3.0 * metric_norm2(m, d) - 2.0 * linear.dot(d) + constant;
    if (!(sum > 0.0)) return {0.0, 1.0};
    return {scale * volume6 * std::abs(volume6), sum * sum * sum};
  }
};

// The squared metric lengths of face f0, f1, f2's edges f0f1, f1f2, f2f0
// (the ball term and the ideal apex both need them).
inline std::array<double, 3> face_edges2(const Sym6& m, const Point& f0, const Point& f1, const Point& f2) {
  return {metric_norm2(m, f1 - f0), metric_norm2(m, f2 - f1), metric_norm2(m, f0 - f2)};
}

// The terms of the ball tet of v (at x) with the face f0, f1, f2 opposite
// v, ordered so that n = (f1 - f0) x (f2 - f0) points towards x, in
// metric m of determinant det_m; edges2 = face_edges2(m, f0, f1, f2).
inline BallTerm ball_term(const Point& x, const Point& f0, const Point& f1, const Point& f2, const Sym6& m,
                          double det_m, const std::array<double, 3>& edges2) {
  BallTerm b;
  b.normal = (f1 - f0).cross(f2 - f0);
  b.volume0 = b.normal.dot(x - f0);
  const Eigen::Vector3d e0 = f0 - x, e1 = f1 - x, e2 = f2 - x;
  b.linear = sym_times(m, e0 + e1 + e2);
  b.constant = metric_norm2(m, e0) + metric_norm2(m, e1) + metric_norm2(m, e2) + edges2[0] + edges2[1] + edges2[2];
  b.scale = kMeanRatioCubedNorm * det_m;
  return b;
}

struct SmoothScratch : ScratchGeneration {
  TetList ball;
  VertexList neighbours;
  boost::container::small_vector<Point, 96> trials;
  boost::container::small_vector<GeoParam, 32> trial_params;  // on a model: each trial's parameters
  // The metric of each ball tet, and its terms.
  boost::container::small_vector<Sym6, 64> metrics;
  boost::container::small_vector<BallTerm, 64> terms;
  // The smallest mean ratio of the ball where v stands (MinQuality's trials).
  double ball_min_quality = 0.0;
};

namespace detail {
// The apex of the regular tet on face (p, q, r) in metric m, on the side
// of n = (q - p) x (r - p): the face's centroid plus the height sqrt(2/3) l
// along the face's unit normal in the metric, l the mean metric length of
// the face's edges. That normal is the direction d = m^-1 n (m-orthogonal
// to the face's edges), here adj(m) n, whose metric length is
// sqrt(det(m) n . d): no factorisation of m. edges2 = face_edges2(m, p, q, r).
inline Point ideal_apex(const Point& p, const Point& q, const Point& r, const Eigen::Vector3d& n, const Sym6& m,
                        double det_m, const std::array<double, 3>& edges2) {
  const Point centroid = (p + q + r) / 3.0;
  const Eigen::Vector3d d = sym_times(adjugate(m), n);
  const double d_norm2 = det_m * n.dot(d);
  if (!(d_norm2 > 0.0)) return centroid;
  const double len = (std::sqrt(edges2[0]) + std::sqrt(edges2[1]) + std::sqrt(edges2[2])) / 3.0;
  return centroid + (std::sqrt(2.0 / 3.0) * len / std::sqrt(d_norm2)) * d;
}
}  // namespace detail

// The find step of smoothing: v's ball and neighbours into the scratch
// (the pass locks them, then decide_smoothing reads them).
inline void find_smoothing_cavity(const Mesh& mesh, VertexId v, SmoothScratch& s) {
  vertex_ball(mesh, v, s.ball);
  vertex_neighbours(mesh, s.ball, v, s.neighbours);
}

// The tets of v's ball (from find_smoothing_cavity) with v at p: the
// preview of a move of v.
inline void ball_moved_to(const Mesh& mesh, VertexId v, const TetList& ball, const Point& p, PlannedTets& out) {
  out.clear();
  for (TetId t : ball) out.push_back({mesh.tet(t), tet_points_moved(mesh, mesh.tet(t), v, p)});
}

// Is every tet of v's ball positively oriented (Precision) with v at p?
inline bool ball_positive_at(const Mesh& mesh, VertexId v, const TetList& ball, const Point& p) {
  for (TetId t : ball) {
    const TetPoints pts = tet_points_moved(mesh, mesh.tet(t), v, p);
    if (!positive_tet(pts[0], pts[1], pts[2], pts[3])) return false;
  }
  return true;
}

struct SmoothPlan {
  Point to;
  GeoParam geo;  // on a model: the parameters of `to`
  // With a background: v's metric at `to`, sampled when decided.
  VertexMetric metric{};
  bool sampled = false;
};

template <Geometry G>
bool boundary_trials_on_model(const Mesh& mesh, VertexId v, SmoothScratch& s, const G& geometry);

namespace detail {

// The ball terms of v (s.metrics, s.terms) and the optimal point: the mean
// of the ideal apexes of its faces. Face (t[kFaceVertex[iv]]) is oriented
// outwards, so the apex lies on its negative side; two vertices swap. The
// same swapped order gives the inward normal of the ball terms.
template <MetricSpace S>
Point ball_terms_and_optimum(const Mesh& mesh, VertexId v, SmoothScratch& s) {
  const Point x = mesh.point(v);
  s.metrics.clear();
  s.terms.clear();
  for (TetId t : s.ball) s.metrics.emplace_back(S::tet_metric(mesh, mesh.tet(t)));
  Point optimal = Point::Zero();
  for (std::size_t i = 0; i < s.ball.size(); ++i) {
    const auto& tv = mesh.tet(s.ball[i]);
    const auto f = face_vertices(tv, local_index(tv, v));
    const Point& f0 = mesh.point(f[0]);
    const Point& f1 = mesh.point(f[2]);
    const Point& f2 = mesh.point(f[1]);
    const Sym6& m = s.metrics[i];
    const double det = spd_determinant(m);
    const std::array<double, 3> edges2 = face_edges2(m, f0, f1, f2);
    s.terms.emplace_back(ball_term(x, f0, f1, f2, m, det, edges2));
    optimal += ideal_apex(f0, f1, f2, s.terms.back().normal, m, det, edges2);
  }
  return optimal / static_cast<double>(s.ball.size());
}

// An interior vertex's trials: towards the optimal point (all, half, a
// quarter of the way) and halfway to its neighbours' mean; then, tried
// only when none of those improved (from the returned index on), a
// quarter of the way to each opposite face's centroid.
inline std::size_t interior_trials(const Mesh& mesh, VertexId v, const Point& optimal, SmoothScratch& s) {
  const Point x = mesh.point(v);
  for (double w : {1.0, 0.5, 0.25}) s.trials.emplace_back(x + w * (optimal - x));
  Point mean = Point::Zero();
  for (VertexId u : s.neighbours) mean += mesh.point(u);
  mean /= static_cast<double>(s.neighbours.size());
  s.trials.emplace_back(x + 0.5 * (mean - x));
  const std::size_t secondary = s.trials.size();
  for (TetId t : s.ball) {
    const auto& tv = mesh.tet(t);
    const auto f = face_vertices(tv, local_index(tv, v));
    const Point c = (mesh.point(f[0]) + mesh.point(f[1]) + mesh.point(f[2])) / 3.0;
    s.trials.emplace_back(x + 0.25 * (c - x));
  }
  return secondary;
}

// A surface vertex off any model: its boundary faces must be coplanar
// (within flat_tolerance); trials towards the midpoints of their edges
// opposite v and towards the optimal point projected on their plane.
// False when they are not coplanar.
inline bool flat_surface_trials(const Mesh& mesh, VertexId v, const Point& optimal, double flat_tolerance,
                                SmoothScratch& s) {
  const Point x = mesh.point(v);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (TetId t : s.ball) {
    const auto& tv = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      if (tv[f] == v || !mesh.is_surface_face(t, f)) continue;
      const auto fv = face_vertices(tv, f);
      const Eigen::Vector3d n = face_normal(mesh, fv[0], fv[1], fv[2]);
      if (normal.squaredNorm() == 0.0)
        normal = n;
      else if (normal_deviation(normal, n) > flat_tolerance)
        return false;
      for (int k = 0; k < 3; ++k) {
        if (fv[k] == v) {
          const Point mid = 0.5 * (mesh.point(fv[(k + 1) % 3]) + mesh.point(fv[(k + 2) % 3]));
          for (double w : {0.5, 0.25}) s.trials.emplace_back(x + w * (mid - x));
        }
      }
    }
  }
  if (normal.squaredNorm() == 0.0) return false;
  normal.normalize();
  const Point projected = optimal - (optimal - x).dot(normal) * normal;
  for (double w : {1.0, 0.5, 0.25}) s.trials.emplace_back(x + w * (projected - x));
  return true;
}

// A ridge vertex off any model: its two ridge neighbours must lie on a
// straight line through it (within flat_tolerance); trials towards each
// (a half, a quarter, a tenth of the way). False otherwise.
inline bool straight_ridge_trials(const Mesh& mesh, VertexId v, double flat_tolerance, SmoothScratch& s) {
  const Point x = mesh.point(v);
  VertexId ends[2] = {kNoId, kNoId};
  int k = 0;
  for (VertexId u : s.neighbours)
    if (mesh.is_ridge(v, u)) {
      if (k < 2) ends[k] = u;
      ++k;
    }
  if (k != 2) return false;
  const Eigen::Vector3d d1 = mesh.point(ends[0]) - x, d2 = mesh.point(ends[1]) - x;
  if (normal_deviation(d1, d2) > flat_tolerance) return false;
  for (const auto& d : {d1, d2})
    for (double w : {0.5, 0.25, 0.1}) s.trials.emplace_back(x + w * d);
  return true;
}

// The change of the ball's volume when v moves to p.
inline double ball_volume_change(const Mesh& mesh, VertexId v, std::span<const TetId> ball, const Point& p) {
  double delta = 0.0;
  for (TetId t : ball) {
    const auto& tv = mesh.tet(t);
    TetPoints x{mesh.point(tv[0]), mesh.point(tv[1]), mesh.point(tv[2]), mesh.point(tv[3])};
    const double before = tet_volume(x[0], x[1], x[2], x[3]);
    x[static_cast<std::size_t>(local_index(tv, v))] = p;
    delta += tet_volume(x[0], x[1], x[2], x[3]) - before;
  }
  return delta;
}

// Does moving v to p with the metric vm raise the smallest mean ratio of
// its ball above `before` (every tet's metric interpolated with vm at v)?
template <MetricSpace S>
bool raises_worst_tet_with(const Mesh& mesh, VertexId v, std::span<const TetId> ball, const Point& p,
                           const VertexMetric& vm, double before) {
  for (TetId t : ball) {
    const auto& tv = mesh.tet(t);
    const double after = mean_ratio(tet_points_moved(mesh, tv, v, p), S::tet_metric_with(mesh, tv, v, vm));
    if (!improves_min_quality(before, after)) return false;
  }
  return true;
}

// The best of s.trials under MinQuality (scores Q^3), from the ball terms:
// the smallest mean ratio (cubed) of the ball with v at a trial, each
// trial stopping at the first tet at or below the best so far (tested
// without a division) and starting from the tet that stopped the last one
// (the ball's bottleneck stops most failing trials at once). `admissible`
// says whether a trial that scores better may be kept.
template <class Admissible>
Decision<SmoothPlan> best_trial_by_mean_ratio(const Mesh& mesh, VertexId v, SmoothScratch& s, std::size_t secondary,
                                              Admissible&& admissible) {
  const Point x = mesh.point(v);
  const std::size_t n = s.ball.size();
  std::size_t first = 0;
  auto min_quality3_at = [&](const Point& p, double floor3) {
    const Eigen::Vector3d d = p - x;
    double num_min = std::numeric_limits<double>::infinity(), den_min = 1.0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = first + k < n ? first + k : first + k - n;
      const auto [num, den] = s.terms[i].quality3_parts(s.metrics[i], d);
      if (num <= floor3 * den) {
        first = i;
        return num / den;
      }
      if (num * den_min < num_min * den) {
        num_min = num;
        den_min = den;
      }
    }
    return num_min / den_min;
  };
  // The ball's quality now, kept in s for the check in the sampled
  // metric: the cache, or the terms (no tet metric; not stored, since a
  // move, the usual outcome of smoothing every vertex, makes them stale
  // at once). Cube roots only where a mean ratio meets
  // the cache's: min and cbrt commute, so one for the uncached tets and
  // one for the best trial.
  double q_old = std::numeric_limits<double>::infinity(), q3_uncached = q_old;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = mesh.cached_quality(s.ball[i]);
    if (q != Mesh::kUnknownQuality) {
      q_old = std::min(q_old, q);
    } else {
      const auto [num, den] = s.terms[i].quality3_parts(s.metrics[i], Eigen::Vector3d::Zero());
      q3_uncached = std::min(q3_uncached, num / den);
    }
  }
  q_old = std::min(q_old, std::cbrt(q3_uncached));
  s.ball_min_quality = q_old;
  double q3_best = q_old * q_old * q_old;
  std::size_t best = s.trials.size();
  auto improves = [&] { return best != s.trials.size() && improves_min_quality(q_old, std::cbrt(q3_best)); };
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    if (i == secondary && improves()) break;
    const Point& p = s.trials[i];
    const double q3 = min_quality3_at(p, q3_best);
    if (q3 > q3_best && admissible(p)) {
      q3_best = q3;
      best = i;
    }
  }
  if (!improves()) return Refusal::rejected;
  return SmoothPlan{s.trials[best], s.trial_params.empty() ? GeoParam{} : s.trial_params[best]};
}

// The best of s.trials under any other criterion: its smallest score over
// the ball at each trial, each new tet passing `accept`'s shape floor.
template <MetricSpace S, class Criterion, class Admissible>
Decision<SmoothPlan> best_trial_by_criterion(const Mesh& mesh, VertexId v, const SmoothScratch& s,
                                             std::size_t secondary, const Acceptance<S, Criterion>& accept,
                                             Admissible&& admissible) {
  auto r = accept.replacing(mesh, view(s.ball));
  auto score_at = [&](const Point& p) {
    double q = std::numeric_limits<double>::infinity();
    for (TetId t : s.ball) {
      const TetPoints pts = tet_points_moved(mesh, mesh.tet(t), v, p);
      if (!r.shape_admits(mesh.tet(t), pts)) return -std::numeric_limits<double>::infinity();
      q = std::min(q, Criterion::template tet_score_at<S>(mesh, mesh.tet(t), pts));
    }
    return q;
  };
  double best_score = min_score_of<Criterion, S>(mesh, view(s.ball));
  std::size_t best = s.trials.size();
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    if (i == secondary && best != s.trials.size()) break;
    const Point& p = s.trials[i];
    const double score = score_at(p);
    if (score > Criterion::bar(best_score) && admissible(p)) {
      best_score = score;
      best = i;
    }
  }
  if (best == s.trials.size()) return Refusal::rejected;
  return SmoothPlan{s.trials[best], s.trial_params.empty() ? GeoParam{} : s.trial_params[best]};
}

}  // namespace detail

// Decide where vertex v moves; s holds its cavity (find_smoothing_cavity),
// whose vertices the caller holds. The trials by vertex class (interior;
// on the model; a flat surface; a straight ridge), then the best of them
// that keeps the ball positive (P) and leaves no more of v's edges outside
// the unit band than now (a move for quality must not cost conformity:
// without this rule, smoothing every vertex for quality took 3 points of
// conformity on polar-1). Under a criterion whose score is the mean ratio
// cubed (MinQuality) trials are scored from the ball terms; under any
// other, from its scores at the trial position, with the shape floor.
template <MetricSpace S, class Criterion = MinQuality, Geometry G = ModelOrFacets>
Decision<SmoothPlan> decide_smoothing(const Mesh& mesh, VertexId v, SmoothScratch& s, const SmoothOptions& o,
                                      const G& geometry = {}) {
  const VertexClass cls = mesh.vertex_class(v);
  // A vertex of an internal surface moves within it as a boundary vertex
  // does within its surface (its faces on both sides stay on the surface).
  if (cls == VertexClass::corner || mesh.is_fixed(v)) return Refusal::not_applicable;
  if (s.ball.empty()) return Refusal::not_applicable;
  const Point x = mesh.point(v);
  s.trials.clear();
  s.trial_params.clear();
  const Point optimal = detail::ball_terms_and_optimum<S>(mesh, v, s);
  // Trials from `secondary` on are tried only when none before improved.
  std::size_t secondary = std::numeric_limits<std::size_t>::max();
  if (cls == VertexClass::interior) {
    secondary = detail::interior_trials(mesh, v, optimal, s);
  } else if (geometry.places(mesh, v)) {
    if (!boundary_trials_on_model(mesh, v, s, geometry)) return Refusal::not_applicable;
  } else if (cls == VertexClass::surface) {
    if (!detail::flat_surface_trials(mesh, v, optimal, o.flat_tolerance, s)) return Refusal::not_applicable;
  } else if (!detail::straight_ridge_trials(mesh, v, o.flat_tolerance, s)) {
    return Refusal::not_applicable;
  }
  const auto& mv = S::vertex_metric(mesh, v);
  auto out_of_range = [&](const Point& p) {
    int n = 0;
    for (VertexId u : s.neighbours) n += !ugawg_length_in(kUnitBand, mesh.point(u) - p, mv, S::vertex_metric(mesh, u));
    return n;
  };
  const int bad_old = out_of_range(x);
  auto admissible = [&](const Point& p) { return out_of_range(p) <= bad_old && ball_positive_at(mesh, v, s.ball, p); };
  Decision<SmoothPlan> d = Refusal::rejected;
  if constexpr (CriterionTraits<Criterion>::score_is_mean_ratio_cubed)
    d = detail::best_trial_by_mean_ratio(mesh, v, s, secondary, admissible);
  else
    d = detail::best_trial_by_criterion(mesh, v, s, secondary, Acceptance<S, Criterion>(o.shape_floor), admissible);
  // With a background, v's metric at the chosen point is sampled here, once
  // (the apply stores it), and the move must still hold in that metric: no
  // more of v's edges outside the unit band than there were, and (under
  // MinQuality, a ball below o.resample_below) the ball's worst tet
  // raised. The trials were measured in v's metric where it stands, which
  // a field given on a coarse mesh may change much over the move. (An
  // analytic metric is evaluated at the apply, as the UGAWG reference
  // outputs were made.)
  if (!d) return d;
  if (o.scope.metric.background != nullptr) {
    SmoothPlan plan = d.plan();
    const std::array<VertexId, 1> self{v};
    plan.metric = o.scope.metric.at(mesh, plan.to, self);
    plan.sampled = true;
    int n = 0;
    for (VertexId u : s.neighbours)
      n += !ugawg_length_in(kUnitBand, mesh.point(u) - plan.to, plan.metric.m, S::vertex_metric(mesh, u));
    if (n > bad_old) return Refusal::rejected;
    if constexpr (CriterionTraits<Criterion>::score_is_mean_ratio_cubed)
      if (s.ball_min_quality < o.resample_below &&
          !detail::raises_worst_tet_with<S>(mesh, v, view(s.ball), plan.to, plan.metric, s.ball_min_quality))
        return Refusal::rejected;
    d = plan;
  }
  // Last, once nothing else refuses: a boundary move's change of volume
  // from the budget (the ball's volume with v moved against now).
  if (o.volume_budget != nullptr && cls != VertexClass::interior && !geometry.places(mesh, v) &&
      !o.volume_budget->take(detail::ball_volume_change(mesh, v, view(s.ball), d.plan().to)))
    return Refusal::rejected;
  return d;
}

// The trials of boundary vertex v on the model (s.trials and their
// parameters in s.trial_params); false when v has no parameters or no
// trial. A surface vertex: towards the midpoint of each outer edge of its
// boundary faces (halfway and a quarter of the way) and towards the mean
// of its surface neighbours; a ridge vertex: towards each ridge neighbour
// (a half, a quarter, a tenth of the way along the curve).
template <Geometry G>
bool boundary_trials_on_model(const Mesh& mesh, VertexId v, SmoothScratch& s, const G& geometry) {
  if (!mesh.has_geo_params() || !mesh.geo_param(v).valid()) return false;
  auto add = [&](std::span<const VertexId> parents, std::span<const double> w, SurfaceId surface) {
    const GeoParam g = geometry.boundary_vertex(mesh, parents, w, surface);
    if (!g.valid()) return;
    s.trials.emplace_back(geometry.point(g));
    s.trial_params.emplace_back(g);
  };
  if (mesh.vertex_class(v) == VertexClass::ridge) {
    for (VertexId u : s.neighbours) {
      if (!mesh.is_ridge(v, u)) continue;
      const std::array<VertexId, 2> ends{v, u};
      for (double w : {0.5, 0.25, 0.1}) {
        const std::array<double, 2> weights{1.0 - w, w};
        add(ends, weights, 0);
      }
    }
    return !s.trials.empty();
  }
  const SurfaceId surface = mesh.geo_param(v).dim == 2 ? mesh.geo_param(v).tag : 0;
  if (surface <= 0) return false;
  boost::container::small_vector<VertexId, 32> around;  // v's neighbours on its boundary faces
  for (TetId t : s.ball) {
    const auto& tv = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      if (tv[f] == v || !mesh.is_surface_face(t, f)) continue;
      const auto fv = face_vertices(tv, f);
      const int k = fv[0] == v ? 0 : fv[1] == v ? 1 : 2;
      const std::array<VertexId, 3> parents{v, fv[(k + 1) % 3], fv[(k + 2) % 3]};
      for (double w : {0.5, 0.25}) {
        const std::array<double, 3> weights{1.0 - w, 0.5 * w, 0.5 * w};
        add(parents, weights, surface);
      }
      for (int j = 1; j <= 2; ++j)
        if (std::find(around.begin(), around.end(), parents[j]) == around.end()) around.emplace_back(parents[j]);
    }
  }
  if (around.size() >= 2) {
    boost::container::small_vector<VertexId, 33> parents{v};
    parents.insert(parents.end(), around.begin(), around.end());
    boost::container::small_vector<double, 33> weights(parents.size(), 0.5 / static_cast<double>(around.size()));
    weights[0] = 0.5;
    add(std::span<const VertexId>(parents.data(), parents.size()),
        std::span<const double>(weights.data(), weights.size()), surface);
  }
  return !s.trials.empty();
}

// Apply: v moves to the plan's point (and takes the metric there when an
// analytic metric or a background is given).
inline void apply_smoothing(Mesh& mesh, VertexId v, const SmoothPlan& plan, const SmoothScratch& s,
                            const SmoothOptions& o) {
  mesh.point(v) = plan.to;
  if (plan.geo.valid()) mesh.set_geo_param(v, plan.geo);
  for (TetId t : s.ball) mesh.touch_tet(t);
  if (plan.sampled) {
    set_vertex_metric(mesh, v, plan.metric);
  } else if (o.scope.metric) {
    const std::array<VertexId, 1> self{v};
    set_vertex_metric(mesh, v, o.scope.metric.at(mesh, plan.to, self));
  }
}

// The steps every move of one vertex shares (smoothing, projection onto
// the model): the item is the vertex, held first; its cavity is its ball,
// whose other vertices are held next; nothing is created; the plan's tets
// are the ball with the vertex moved. An operation that derives from it
// writes its own decide and apply (and is built as Op{{}, options, ...}).
struct VertexMoveSteps {
  using Item = VertexId;
  using Scratch = SmoothScratch;
  using Plan = SmoothPlan;

  PassRoom room() const { return {.max_vertices = 0, .max_tets = 0, .vertices_per_item = 0, .tets_per_item = 0}; }
  Found seed(const Mesh&, VertexId v, Scratch&, VertexList& hold) const {
    hold.emplace_back(v);
    return Found::cavity;
  }
  Found find(const Mesh& mesh, VertexId v, Scratch& s, VertexList& hold) const {
    find_smoothing_cavity(mesh, v, s);
    hold.insert(hold.end(), s.neighbours.begin(), s.neighbours.end());
    return Found::cavity;
  }
  void preview(const Mesh& mesh, VertexId v, const Plan& plan, const Scratch& s, PlannedTets& out) const {
    ball_moved_to(mesh, v, s.ball, plan.to, out);
  }
};

// Vertex smoothing as an operation.
template <MetricSpace S, class Criterion = MinQuality, Geometry G = ModelOrFacets>
struct Smoothing : VertexMoveSteps {
  static constexpr std::string_view name = "smooth";
  SmoothOptions options;
  G geometry{};

  Decision<Plan> decide(const Mesh& mesh, VertexId v, Scratch& s) const {
    return decide_smoothing<S, Criterion>(mesh, v, s, options, geometry);
  }
  void apply(Mesh& mesh, VertexId v, const Plan& plan, Scratch& s) const { apply_smoothing(mesh, v, plan, s, options); }
};

// The smoothing pass over the vertices of tets below o.below.
template <MetricSpace S, Concurrency C, class Criterion = MinQuality, Geometry G = ModelOrFacets>
OperatorStats smooth_vertices(Mesh& mesh, const SmoothOptions& o = {}, const G& geometry = {}) {
  Stopwatch clock;
  const std::vector<std::uint8_t> changed = changed_vertices<C>(mesh, o.scope.changed_since);
  // The vertices to try, marked by a sweep over the tets (relaxed byte
  // stores: two parts may mark one vertex), then listed from the marks
  // in id order: sorted and unique without a list of four ids per tet
  // or a serial sort.
  std::vector<std::uint8_t> marked(mesh.vertex_capacity(), 0);
  const std::size_t nt = mesh.tet_capacity();
  const std::size_t parts = sweep_parts<C>(nt);
  C::parallel_for(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(nt, parts, p);
    for (auto t = static_cast<TetId>(first); t < last; ++t)
      if (mesh.tet_alive(t) && cached_mean_ratio<S>(mesh, t) < o.below)
        for (VertexId v : mesh.tet(t))
          if (changed[v]) std::atomic_ref<std::uint8_t>(marked[v]).store(1, std::memory_order_relaxed);
  });
  const std::vector<VertexId> todo =
      C::template collect<VertexId>(marked.size(), [&](std::size_t v, std::vector<VertexId>& part) {
        if (marked[v] != 0) part.emplace_back(static_cast<VertexId>(v));
      });
  OperatorStats stats = run_pass<C>(mesh, Smoothing<S, Criterion, G>{{}, o, geometry}, todo);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
