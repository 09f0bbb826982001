// Helpers of the operator tests: meshes with work to do, the invariant
// check after every pass, and the policy combinations every operator test
// runs under.
#pragma once

#include <metrica/policies/speculative.hpp>

#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/criterion.hpp>
#include <metrica/pipeline/adapt.hpp>  // the standard stages, compiled in the library
#include <metrica/policies/concurrency.hpp>
#include <metrica/predicates/precision.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <random>
#include <span>
#include <vector>

namespace metrica::test {

inline void set_uniform_metric(Mesh& mesh, double h) {
  std::vector<Sym6> f(mesh.vertex_capacity(), isotropic_metric(h));
  assign_metric(mesh, f);
}

// `metric` evaluated at every vertex.
inline void set_metric_function(Mesh& mesh, const MetricFunction& metric) {
  std::vector<Sym6> f(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) f[v] = metric(mesh.point(v));
  assign_metric(mesh, f);
}

// The UGAWG linear metric with sizes x 2.5: about 300 vertices from the
// 4x4x4 cube (the parallel tests' adaptation, the repair fixture's metric).
inline Sym6 small_linear(const Point& p) {
  Sym6 m = evaluate(AnalyticMetric::linear, p);
  for (double& x : m) x /= 2.5 * 2.5;
  return m;
}

inline void require_valid(const Mesh& mesh, double volume) {
  ValidateOptions o;
  o.expected_volume = volume;
  const auto report = mesh.validate(o);
  INFO(report.to_string());
  REQUIRE(report.ok());
}

template <class S>
double longest(const Mesh& mesh) {
  double l = 0.0;
  for (const auto& [a, b] : unique_edges(mesh)) l = std::max(l, S::edge_length(mesh, a, b));
  return l;
}

// A box whose interior vertices are moved at random by up to `amount` of
// the spacing: tets of every shape, flips and smoothing have work to do.
inline Mesh jittered_box(int n, double amount, std::uint64_t stream) {
  Mesh mesh = make_box({.nx = n, .ny = n, .nz = n});
  auto r = test::rng(stream);
  std::uniform_real_distribution<double> u(-amount / n, amount / n);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_class(v) == VertexClass::interior) mesh.point(v) += test::draw_point(u, r);
  return mesh;
}

// Accepts every valid configuration: exercises the topology alone.
struct AlwaysFlip {
  template <MetricSpace S, Precision P>
  static bool prefers(const Mesh&, std::span<const TetVertices>, std::span<const TetVertices>) {
    return true;
  }
};

inline std::vector<TetVertices> sorted_tets(const Mesh& mesh) {
  std::vector<TetVertices> out;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t)
    if (mesh.tet_alive(t)) {
      TetVertices v = mesh.tet(t);
      std::sort(v.begin(), v.end());
      out.push_back(v);
    }
  std::sort(out.begin(), out.end());
  return out;
}

template <class S>
double worst_quality(const Mesh& mesh) {
  double q = 1.0;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t)
    if (mesh.tet_alive(t)) q = std::min(q, S::mean_ratio(mesh, mesh.tet(t)));
  return q;
}

// Area of the boundary faces of each surface id.
inline std::map<SurfaceId, double> surface_areas(const Mesh& mesh) {
  std::map<SurfaceId, double> area;
  for_each_boundary_face(mesh, [&](TetId t, int f) {
    const auto v = face_vertices(mesh.tet(t), f);
    area[mesh.surface_id(t, f)] +=
        0.5 * (mesh.point(v[1]) - mesh.point(v[0])).cross(mesh.point(v[2]) - mesh.point(v[0])).norm();
  });
  return area;
}

// A policy combination; Speculative ones with their thread count.
template <class S, class P, class C, int Threads = 0>
struct Policies {
  using Space = S;
  using Precision = P;
  using Concurrency = C;
  static constexpr int threads = Threads;
};

// Speculative pinned to N threads with every list sent to them, as a type:
// for the sweeps and executors tested one by one (each call runs under its
// own SpeculativeScope).
template <int N>
struct SpeculativeOn {
  static constexpr std::string_view name = Speculative::name;
  using OwnerTable = Speculative::OwnerTable;
  using Locks = Speculative::Locks;
  static SpeculativeSettings pinned() { return {.threads = N, .small_list = 0}; }
  static int threads() { return N; }
  template <class T, class F>
  static std::vector<T> collect(std::size_t n, F&& f) {
    const SpeculativeScope scope(pinned());
    return Speculative::collect<T>(n, std::forward<F>(f));
  }
  template <class F>
  static void parallel_for(std::size_t n, F&& f) {
    const SpeculativeScope scope(pinned());
    Speculative::parallel_for(n, std::forward<F>(f));
  }
  template <class It, class Less>
  static void sort(It first, It last, Less less) {
    const SpeculativeScope scope(pinned());
    Speculative::sort(first, last, less);
  }
  template <class Item, class Work>
  static PassTally for_each(Mesh& mesh, std::span<const Item> items, const PassRoom& room, Work&& work) {
    const SpeculativeScope scope(pinned());
    return Speculative::for_each(mesh, items, room, std::forward<Work>(work));
  }
};

// Speculative on T's threads with every list sent to them (no small-list
// rule: the test meshes are small), for the test's lifetime.
template <class T>
struct ExecutorOf {
  SpeculativeScope scope{{.threads = T::threads, .small_list = 0}};
};

}  // namespace metrica::test

// Every Space and Precision under Serial; the Speculative policy with 1,
// 2 and 8 threads (8 on a 2-core machine forces interleavings). A test
// body opens with `const ExecutorOf<T> executor;`. The sanitizer builds
// compile the pipeline for the default space and precision only
// (METRICA_DEFAULT_POLICIES_ONLY): there, those under each executor.
#if METRICA_DEFAULT_POLICIES_ONLY
#define METRICA_POLICY_COMBINATIONS                                                                                \
  metrica::test::Policies<LogEuclidean, Filtered, Serial>,                                                         \
      metrica::test::Policies<LogEuclidean, Filtered, Speculative, 1>,                                            \
      metrica::test::Policies<LogEuclidean, Filtered, Speculative, 2>,                                            \
      metrica::test::Policies<LogEuclidean, Filtered, Speculative, 8>
#else
#define METRICA_POLICY_COMBINATIONS                                                                                \
  metrica::test::Policies<LogEuclidean, Filtered, Serial>, metrica::test::Policies<Anisotropic, Filtered, Serial>, \
      metrica::test::Policies<Isotropic, Filtered, Serial>, metrica::test::Policies<LogEuclidean, Exact, Serial>,  \
      metrica::test::Policies<LogEuclidean, Fast, Serial>,                                                        \
      metrica::test::Policies<LogEuclidean, Filtered, Speculative, 1>,                                            \
      metrica::test::Policies<LogEuclidean, Filtered, Speculative, 2>,                                            \
      metrica::test::Policies<Anisotropic, Filtered, Speculative, 8>
#endif
