// Helpers of the operator tests: meshes with work to do, the invariant
// check after every pass, and the policy combinations every operator test
// runs under.
#pragma once

#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/operators/criterion.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/operators/testing.hpp>
#include <metrica/pipeline/adapt.hpp>  // the standard stages, compiled in the library
#include <metrica/policies/concurrency.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/predicates/precision.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <random>
#include <span>
#include <type_traits>
#include <vector>

namespace metrica::test {

// Built with ThreadSanitizer, whose runs are 5-15 times slower: what the
// sanitizer checks is the threads' accesses, which a short run makes too.
#if defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderThreadSanitizer = true;
#elif defined(__has_feature)
inline constexpr bool kUnderThreadSanitizer = __has_feature(thread_sanitizer);
#else
inline constexpr bool kUnderThreadSanitizer = false;
#endif

// Exact runs every predicate in rational arithmetic, about 20x slower than
// Filtered, and ThreadSanitizer slows every run: a whole adaptation under
// either takes at most two cycles, one quality pass and one repair round
// (`rules`: AdaptOptions or a Pipeline).
template <class P, class Rules>
void shorten_when_slow(Rules& rules) {
  if constexpr (std::is_same_v<P, Exact> || kUnderThreadSanitizer) {
    rules.max_cycles = std::min(rules.max_cycles, 2);
    rules.quality_passes = std::min(rules.quality_passes, 1);
    rules.repair_rounds = std::min(rules.repair_rounds, 1);
  }
}

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

// The 3x3x3-hex box with small_linear at its vertices (the pipeline tests'
// start).
inline Mesh small_linear_box() {
  Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  set_metric_function(mesh, small_linear);
  return mesh;
}

// The live vertices, in id order.
inline std::vector<VertexId> all_vertices(const Mesh& mesh) {
  std::vector<VertexId> out;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) out.push_back(v);
  return out;
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
  auto r = test::rng(stream);
  return metrica::jittered_box(n, amount, r);
}

// Accepts every valid configuration: exercises the topology alone.
struct AlwaysFlip {
  template <MetricSpace S>
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

}  // namespace metrica::test

// Every Space and Precision under Serial; the Speculative policy with 1,
// 2 and 8 threads (8 on a 2-core machine forces interleavings). A test
// body opens with `const ExecutorOf<T> executor;`. The sanitizer builds
// compile the pipeline for the default space and precision only
// (METRICA_DEFAULT_POLICIES_ONLY): there, those under each executor; the
// ThreadSanitizer build (METRICA_TSAN) only those that run threads.
#if METRICA_TSAN
#define METRICA_POLICY_COMBINATIONS \
  metrica::Policies<LogEuclidean, Filtered, Speculative, 2>, metrica::Policies<LogEuclidean, Filtered, Speculative, 8>
#elif METRICA_DEFAULT_POLICIES_ONLY
#define METRICA_POLICY_COMBINATIONS                                                                             \
  metrica::Policies<LogEuclidean, Filtered, Serial>, metrica::Policies<LogEuclidean, Filtered, Speculative, 1>, \
      metrica::Policies<LogEuclidean, Filtered, Speculative, 2>,                                                \
      metrica::Policies<LogEuclidean, Filtered, Speculative, 8>
#else
#define METRICA_POLICY_COMBINATIONS                                                                             \
  metrica::Policies<LogEuclidean, Filtered, Serial>, metrica::Policies<Anisotropic, Filtered, Serial>,          \
      metrica::Policies<Isotropic, Filtered, Serial>, metrica::Policies<LogEuclidean, Exact, Serial>,           \
      metrica::Policies<LogEuclidean, Fast, Serial>, metrica::Policies<LogEuclidean, Filtered, Speculative, 1>, \
      metrica::Policies<LogEuclidean, Filtered, Speculative, 2>,                                                \
      metrica::Policies<Anisotropic, Filtered, Speculative, 8>
#endif
