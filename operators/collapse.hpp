// Edge collapse (seed, section 3.3): a short edge ab disappears by merging
// a into b. The ball of a is the cavity; its tets that hold b vanish and
// the others have a renamed b (cavity.hpp with renaming).
//
// Rules that keep the boundary what it was (decide, before any write):
//   - a corner or a required vertex never moves;
//   - a ridge vertex moves only along a ridge edge (b on its ridge);
//   - a surface vertex moves only along a boundary edge (b on its surface),
//     and the boundary faces it drags keep their plane (normal deviation
//     below a tolerance: 0 on flat boundaries, so the volume is conserved);
//   - every new tet is positively oriented (Precision), no new edge is
//     longer than max_new_length, and the worst new tet is above the
//     quality floor or no worse than the worst tet of the old ball;
//   - the faces still match one to one (plan_cavity: the link condition).
// When neither end may take the other's place without making long edges,
// two interior ends merge at the edge's metric midpoint instead.
#pragma once

#include <metrica/operators/cavity.hpp>
#include <metrica/operators/edge_queue.hpp>
#include <metrica/operators/flips.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/operator_stats.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <cmath>
#include <vector>

namespace metrica {

struct CollapseOptions {
  // Edges shorter than this (metric length) are collapsed.
  double min_length = 1.0 / std::sqrt(2.0);
  // A collapse may not create an edge longer than this. Above the split
  // threshold the two operators undo a little of each other's work, but
  // more short edges go: on the UGAWG linear case 1.5 gave 92.6% of edges
  // in range against 91.0% for sqrt 2, and 86.7% for 1.7.
  double max_new_length = 1.5;
  double quality_floor = 0.1;
  // Largest 1 - cos between a boundary face's normal before and after.
  double max_normal_deviation = 1.0 - std::cos(2.0 * 3.14159265358979323846 / 180.0);
  // When set, a collapse must raise the worst tet of the ball (both balls
  // for a merge at the midpoint): the repair rounds collapse edges of any
  // length at a poor tet, and only to lift it.
  bool require_gain = false;
  // When set, a vertex merged at an edge's midpoint takes this metric.
  const MetricFunction* metric = nullptr;
  // Only edges with an end whose ball changed since this epoch are tried
  // (0: all); a collapse reads the two balls only.
  Mesh::Epoch changed_since = 0;
};

struct CollapseScratch {
  TetList ball, ball_b;
  Shell shell;
  VertexList neighbours, neighbours_b;  // of a, of b
  NewTets old_tets, new_tets, dragged;
  boost::container::small_vector<double, 32> new_quality;  // of new_tets
  CavityPlan plan;
  TetList created;
};

// May vertex a move onto b by the class rules? `boundary_edge`: ab has an
// open shell.
inline bool collapse_allowed(const Mesh& mesh, VertexId a, VertexId b, bool boundary_edge) {
  if (mesh.is_required(a)) return false;
  switch (mesh.vertex_class(a)) {
    case VertexClass::corner: return false;
    case VertexClass::ridge: return mesh.is_ridge(a, b);
    case VertexClass::surface: return boundary_edge;
    case VertexClass::interior: return true;
  }
  return false;
}

// Decide and apply the collapse of a onto b, with b left where it is or,
// when `moved` is given (both ends interior), moved to that point with
// metric `moved_metric` (the merge at the edge's metric midpoint, which
// makes shorter edges than either end). The caller holds the locks on the
// vertices of ball(a) and ball(b) (s.ball, s.ball_b, s.neighbours and
// s.neighbours_b filled).
template <MetricSpace S, Precision P>
FlipResult collapse_edge(Mesh& mesh, VertexId a, VertexId b, CollapseScratch& s, const CollapseOptions& o,
                         const Point* moved = nullptr, const VertexMetric* moved_metric = nullptr) {
  if (!edge_shell(mesh, a, b, s.ball, s.shell)) return FlipResult::not_applicable;
  if (!collapse_allowed(mesh, a, b, !s.shell.closed)) return FlipResult::not_applicable;
  if (moved != nullptr && (mesh.vertex_class(b) != VertexClass::interior || mesh.is_required(b)))
    return FlipResult::not_applicable;
  const int ref = mesh.tet_ref(s.ball[0]);
  s.old_tets.clear();
  s.new_tets.clear();
  for (TetId t : s.ball) {
    if (mesh.tet_ref(t) != ref) return FlipResult::not_applicable;
    TetVertices v = mesh.tet(t);
    s.old_tets.push_back(v);
    if (local_index(v, b) >= 0) continue;
    v[local_index(v, a)] = b;
    s.new_tets.push_back(v);
  }
  // The tets of b's ball that b's move drags along (it keeps their topology).
  s.dragged.clear();
  if (moved != nullptr)
    for (TetId t : s.ball_b)
      if (local_index(mesh.tet(t), a) < 0) s.dragged.push_back(mesh.tet(t));
  const Point pb = moved != nullptr ? *moved : mesh.point(b);
  const Sym6 mb = moved_metric != nullptr ? moved_metric->m : S::vertex_metric(mesh, b);
  auto points_of = [&](const TetVertices& t) {
    TetPoints x = detail::tet_points(mesh, t);
    x[local_index(t, b)] = pb;
    return x;
  };
  // The checks run cheapest first; the mean ratios (a tensor exponential
  // each in the log-Euclidean space) come last.
  for (const auto* list : {&s.new_tets, &s.dragged})
    for (const auto& t : *list) {
      const TetPoints x = points_of(t);
      if (P::orient3d(x[0], x[1], x[2], x[3]) <= 0) return FlipResult::rejected;
    }
  // New edges: b to a's neighbours; when b moves, all of b's edges too.
  for (const auto* list : {&s.neighbours, &s.neighbours_b}) {
    if (list == &s.neighbours_b && moved == nullptr) break;
    for (VertexId x : *list)
      if (x != a && x != b && ugawg_length(mesh.point(x) - pb, mb, S::vertex_metric(mesh, x)) > o.max_new_length)
        return FlipResult::rejected;
  }
  if (mesh.vertex_class(a) != VertexClass::interior) {
    // Boundary faces through a (and not b) keep their plane.
    for (TetId t : s.ball) {
      const auto& v = mesh.tet(t);
      if (local_index(v, b) >= 0) continue;
      for (int f = 0; f < 4; ++f) {
        if (v[f] == a || mesh.neighbour(t, f).valid()) continue;
        auto fv = face_vertices(v, f);
        const Eigen::Vector3d before = face_normal(mesh, fv[0], fv[1], fv[2]);
        for (auto& x : fv)
          if (x == a) x = b;
        const Eigen::Vector3d after = face_normal(mesh, fv[0], fv[1], fv[2]);
        if (before.dot(after) <= 0.0 || normal_deviation(before, after) > o.max_normal_deviation)
          return FlipResult::rejected;
      }
    }
  }
  if (!plan_cavity(mesh, view(s.ball), view(s.new_tets), s.plan, a, b)) return FlipResult::rejected;
  // Refused when the worst new tet is below the floor and below the worst
  // old one: when some new tet is below both.
  // With require_gain, refused unless every new tet beats the worst old.
  double q_old = Mesh::kUnknownQuality;
  auto worst_old = [&] {
    if (q_old == Mesh::kUnknownQuality) {
      q_old = std::numeric_limits<double>::infinity();
      for (TetId u : s.ball) q_old = std::min(q_old, cached_mean_ratio<S>(mesh, u));
      if (moved != nullptr)
        for (TetId u : s.ball_b) q_old = std::min(q_old, cached_mean_ratio<S>(mesh, u));
    }
    return q_old;
  };
  s.new_quality.clear();
  for (const auto* list : {&s.new_tets, &s.dragged})
    for (const auto& t : *list) {
      const double q = S::mean_ratio(mesh, t, points_of(t));
      if (list == &s.new_tets) s.new_quality.push_back(q);
      if (o.require_gain && q <= worst_old()) return FlipResult::rejected;
      if (q >= o.quality_floor) continue;
      if (q < worst_old()) return FlipResult::rejected;
    }
  apply_cavity(mesh, view(s.ball), view(s.new_tets), s.plan, ref, s.created);
  // The new tets' mean ratios, measured above at their final points in
  // their final metric, go to the quality cache (not when b moves: its
  // metric changes below).
  if (moved == nullptr)
    for (std::size_t i = 0; i < s.created.size(); ++i) mesh.cache_quality(s.created[i], s.new_quality[i]);
  mesh.merge_edge_tags(a, b, view(s.neighbours));
  mesh.remove_vertex(a);
  if (moved != nullptr) {
    mesh.point(b) = pb;
    mesh.set_metric(b, moved_metric->m, moved_metric->log_m);
    for (TetId t : s.ball_b)
      if (mesh.tet_alive(t)) mesh.touch_tet(t);  // dragged along
  }
  return FlipResult::applied;
}

// The collapse pass: edges shorter than min_length, shortest first; each
// tries to remove its end of lower class (interior before surface before
// ridge), then the other.
template <MetricSpace S, Precision P, Concurrency C>
OperatorStats collapse_edges(Mesh& mesh, const CollapseOptions& o = {}) {
  Stopwatch clock;
  OperatorStats stats;
  const auto todo = edges_beyond<S, C>(mesh, o.min_length, EdgeOrder::shortest_first, o.changed_since);
  struct Scratch {
    CollapseScratch s;
    VertexList cavity;
  };
  std::vector<PerThread<Scratch>> threads(static_cast<std::size_t>(C::threads()));
  auto work = [&](const EdgeCandidate& c, int thread, typename C::Locks& locks) {
    auto& [x, st] = threads[static_cast<std::size_t>(thread)];
    CollapseScratch& s = x.s;
    VertexList& cavity = x.cavity;
    // The two ends first (their balls may then be read), then both balls:
    // the endpoint collapses change ball(from), the merge at the midpoint
    // moves b too.
    if (!locks.acquire({c.a, c.b})) return Attempt::conflict;
    if (!mesh.vertex_alive(c.a) || !mesh.vertex_alive(c.b)) return Attempt::done;
    vertex_ball(mesh, c.a, s.ball);
    vertex_neighbours(mesh, s.ball, c.a, s.neighbours);
    if (std::find(s.neighbours.begin(), s.neighbours.end(), c.b) == s.neighbours.end()) return Attempt::done;  // edge gone
    vertex_ball(mesh, c.b, s.ball_b);
    vertex_neighbours(mesh, s.ball_b, c.b, s.neighbours_b);
    // The cavity: both balls' vertices, the union of the two neighbour
    // lists (each holds the other end).
    cavity = s.neighbours;
    append_new(s.neighbours_b, cavity);
    if (!locks.acquire(view(cavity))) return Attempt::conflict;
    ++st.tried;
    VertexId from = c.a, to = c.b;
    if (mesh.vertex_class(to) < mesh.vertex_class(from)) std::swap(from, to);
    FlipResult r = FlipResult::not_applicable;
    bool rejected = false;
    // The balls and neighbours found for locking are those of the first
    // attempt (the attempts that fail write nothing, so they stay valid
    // for the others).
    if (from != c.a) {
      std::swap(s.ball, s.ball_b);
      std::swap(s.neighbours, s.neighbours_b);
    }
    for (int attempt = 0; attempt < 3 && r != FlipResult::applied; ++attempt) {
      if (attempt == 1) {
        std::swap(from, to);
        std::swap(s.ball, s.ball_b);
        std::swap(s.neighbours, s.neighbours_b);
      }
      if (attempt < 2) {
        r = collapse_edge<S, P>(mesh, from, to, s, o);
      } else {
        if (mesh.vertex_class(from) != VertexClass::interior || mesh.vertex_class(to) != VertexClass::interior) break;
        const auto& ma = S::vertex_metric(mesh, from);
        const auto& mb = S::vertex_metric(mesh, to);
        const Eigen::Vector3d e = mesh.point(to) - mesh.point(from);
        const double t = metric_midpoint(std::sqrt(metric_norm2(ma, e)), std::sqrt(metric_norm2(mb, e)));
        const Point p = mesh.point(from) + t * e;
        const std::array<VertexId, 2> ends{from, to};
        const std::array<double, 2> w{1.0 - t, t};
        const VertexMetric m = new_vertex_metric<S>(mesh, o.metric, ends, w, p);
        r = collapse_edge<S, P>(mesh, from, to, s, o, &p, &m);
      }
      rejected = rejected || r == FlipResult::rejected;
    }
    if (r == FlipResult::applied) ++st.applied;
    else if (rejected) ++st.rejected;
    return Attempt::done;
  };
  // A collapse frees tets (net); a thread reuses its own at once.
  stats.add(C::for_each(mesh, std::span<const EdgeCandidate>(todo), PassRoom{.vertices_per_item = 0, .tets_per_item = 0}, work));
  add_thread_counts(stats, threads);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
