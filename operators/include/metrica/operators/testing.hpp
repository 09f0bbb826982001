// Tools to test an operation, as the library's own tests do
// (docs/writing-an-operator.md, step 3):
//   - jittered_box: a box whose interior vertices are moved at random, so
//     that flips and smoothing have work to do;
//   - check_plans: every item through decide without applying it (the mesh
//     must come out as it went in, but for its quality cache); each plan
//     previewed (no tet inverted under exact predicates, none below the
//     shape floor) and the first plans applied on a copy of the mesh (valid,
//     the same volume, the same area per surface id, the same ridge length);
//   - Policies, ExecutorOf and PolicyCombinations: the policy combinations
//     an operation runs under (every Space and Precision under Serial,
//     Speculative on 1, 2 and 8 threads with every list sent to them).
// Nothing here depends on a test framework: check_plans returns what it
// found, and a test checks `ok()`.
#pragma once

#include <metrica/box.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/predicates/precision.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <span>
#include <string>
#include <tuple>

namespace metrica {

// A box of n x n x n hexes (6 tets each) whose interior vertices are moved
// by up to `amount` of the spacing along each axis, drawn from `rng`.
inline Mesh jittered_box(int n, double amount, std::mt19937_64& rng) {
  Mesh mesh = make_box({.nx = n, .ny = n, .nz = n});
  std::uniform_real_distribution<double> u(-amount / n, amount / n);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_class(v) == VertexClass::interior) {
      const double z = u(rng), y = u(rng), x = u(rng);  // a fixed order of draws
      mesh.point(v) += Point(x, y, z);
    }
  return mesh;
}

// Area of the surface faces (boundary and internal) of each surface id.
inline std::map<SurfaceId, double> surface_areas(const Mesh& mesh) {
  std::map<SurfaceId, double> area;
  for_each_surface_face(mesh, [&](TetId t, int f) {
    const auto v = face_vertices(mesh.tet(t), f);
    area[mesh.face_surface_id(t, f)] +=
        0.5 * (mesh.point(v[1]) - mesh.point(v[0])).cross(mesh.point(v[2]) - mesh.point(v[0])).norm();
  });
  return area;
}

// Total length of the ridge edges.
inline double ridge_length(const Mesh& mesh) {
  double l = 0.0;
  for (const auto& [a, b] : unique_edges(mesh))
    if (mesh.is_ridge(a, b)) l += (mesh.point(b) - mesh.point(a)).norm();
  return l;
}

// A hash of everything but the quality cache: live entities, points,
// metrics, vertex classes, tets, neighbours and surface ids, change stamps
// and the epoch. What decide may not change (operation.hpp).
inline std::uint64_t mesh_fingerprint(const Mesh& mesh) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
  auto mix = [&h](const auto& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < sizeof(value); ++i) h = (h ^ bytes[i]) * 1099511628211ULL;
  };
  mix(mesh.epoch());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    mix(mesh.vertex_alive(v));
    if (!mesh.vertex_alive(v)) continue;
    for (int c = 0; c < 3; ++c) mix(mesh.point(v)[c]);
    if (mesh.has_metric()) mix(mesh.metric(v));
    mix(mesh.vertex_class(v));
  }
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    mix(mesh.tet_alive(t));
    if (!mesh.tet_alive(t)) continue;
    mix(mesh.tet(t));
    mix(mesh.tet_stamp(t));
    for (int f = 0; f < 4; ++f) {
      const FaceRef n = mesh.neighbour(t, f);
      if (n.valid()) {
        mix(n.tet());
        mix(n.face());
      } else {
        mix(mesh.surface_id(t, f));
      }
    }
  }
  return h;
}

struct PlanCheck {
  int plans = 0;        // items decide gave a plan
  int applied = 0;      // plans applied on a copy
  std::string problem;  // the first problem found, empty when none
  bool ok() const { return problem.empty(); }
};

// Every item of `items` through decide (decide_item: no executor, no
// locks), which must leave the mesh as it was but for its quality cache
// (mesh_fingerprint). Each plan's tets, previewed at their final points, must be
// positive under exact predicates and, when floor > 0, of mean ratio at
// least min(floor, the mesh's worst before) in the metric of the tets they
// come from (a tet with the plan's new vertex is skipped: its metric is not
// in the mesh yet). The first `applied_checks` plans are applied on a copy,
// which must pass validate() with the mesh's volume, areas per surface id
// and ridge length.
template <MetricSpace S, Operation Op>
PlanCheck check_plans(const Mesh& mesh, const Op& op, std::span<const typename Op::Item> items, double floor,
                      int applied_checks = 25) {
  PlanCheck r;
  typename Op::Scratch s;
  PlannedTets planned;
  const double worst_before = worst_quality<S>(mesh);
  const auto areas = surface_areas(mesh);
  const double ridges = ridge_length(mesh);
  const double volume = mesh.volume();
  const std::uint64_t fingerprint = mesh_fingerprint(mesh);
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
  for (std::size_t i = 0; i < items.size() && r.ok(); ++i) {
    const auto& item = items[i];
    const auto d = decide_item(mesh, op, item, s);
    if (!d) continue;
    ++r.plans;
    preview_plan(mesh, op, item, d, s, planned);
    if (planned.empty()) r.problem = fmt::format("item {}: a plan that makes no tet", i);
    for (const PlannedTet& t : planned) {
      const auto& x = t.points;
      if (Exact::orient3d(x[0], x[1], x[2], x[3]) <= 0) r.problem = fmt::format("item {}: an inverted tet", i);
      if (floor > 0.0 && std::find(t.vertices.begin(), t.vertices.end(), kNoId) == t.vertices.end() &&
          S::mean_ratio(mesh, t.vertices, t.points) < std::min(floor, worst_before) * (1 - 1e-9))
        r.problem = fmt::format("item {}: a tet of mean ratio {} below the floor {}", i,
                                S::mean_ratio(mesh, t.vertices, t.points), std::min(floor, worst_before));
    }
    if (!r.ok() || r.applied >= applied_checks) continue;
    Mesh copy = mesh;
    typename Op::Scratch s2;
    const auto d2 = decide_item(copy, op, item, s2);
    if (!d2) {
      r.problem = fmt::format("item {}: decided again on a copy, no plan", i);
      continue;
    }
    apply_plan(copy, op, item, d2, s2);
    ++r.applied;
    ValidateOptions vo;
    vo.expected_volume = volume;
    if (const auto report = copy.validate(vo); !report.ok())
      r.problem = fmt::format("item {}: applied, the mesh is invalid\n{}", i, report.to_string());
    const auto after = surface_areas(copy);
    bool same_areas = after.size() == areas.size();
    for (const auto& [id, area] : areas) same_areas = same_areas && after.count(id) && close(after.at(id), area);
    if (r.ok() && !same_areas) r.problem = fmt::format("item {}: applied, a surface's area changed", i);
    if (r.ok() && !close(ridge_length(copy), ridges))
      r.problem = fmt::format("item {}: applied, the ridges' length changed", i);
  }
  if (r.ok() && mesh_fingerprint(mesh) != fingerprint) r.problem = "decide wrote to the mesh (not its quality cache)";
  return r;
}

// A policy combination; Speculative ones with their thread count.
template <class S, class P, class C, int Threads = 0>
struct Policies {
  using Space = S;
  using Precision = P;
  using Concurrency = C;
  static constexpr int threads = Threads;
};

// Speculative on T's threads with every list sent to them (no small-list
// rule: test meshes are small), for the object's lifetime. A test under a
// combination T opens with `const ExecutorOf<T> executor;`.
template <class T>
struct ExecutorOf {
  SpeculativeScope scope{{.threads = T::threads, .small_list = 0}};
};

// Every Space and Precision under Serial; Speculative on 1, 2 and 8 threads
// (8 on a 2-core machine forces interleavings). With doctest:
// TEST_CASE_TEMPLATE_DEFINE("...", T, id) then
// TEST_CASE_TEMPLATE_APPLY(id, PolicyCombinations).
using PolicyCombinations =
    std::tuple<Policies<LogEuclidean, Filtered, Serial>, Policies<Anisotropic, Filtered, Serial>,
               Policies<Isotropic, Filtered, Serial>, Policies<LogEuclidean, Exact, Serial>,
               Policies<LogEuclidean, Fast, Serial>, Policies<LogEuclidean, Filtered, Speculative, 1>,
               Policies<LogEuclidean, Filtered, Speculative, 2>, Policies<Anisotropic, Filtered, Speculative, 8>>;

}  // namespace metrica
