// Change tracking: the per-tet epoch stamps that let a pass try only what
// changed since it last ran, and the per-tet quality cache. The laws: a
// write stamps the tet with the current epoch; a pass restricted to what
// changed since its last run finds nothing to do on an unchanged mesh;
// every cached quality equals a fresh computation (to rounding) after any
// operator.
#include "operator_test_support.hpp"

#include <metrica/metrics/quality_report.hpp>
#include <metrica/pipeline/adapt.hpp>

using namespace metrica;
using namespace metrica::test;

namespace {
// Every cached quality is the value computed now (up to rounding: flips
// fill the cache from their Q^3 scores); returns how many tets have one
// (callers check that the law was not checked on nothing).
template <class S>
std::size_t require_cache_fresh(const Mesh& mesh) {
  std::size_t cached = 0;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t) || mesh.cached_quality(t) == Mesh::kUnknownQuality) continue;
    ++cached;
    REQUIRE(mesh.cached_quality(t) == doctest::Approx(S::mean_ratio(mesh, mesh.tet(t))).epsilon(1e-12));
  }
  return cached;
}
}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("writes stamp tets with the current epoch and compaction keeps the stamps") {
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    const Mesh::Epoch e = mesh.next_epoch();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) CHECK_FALSE(mesh.changed_since(t, e));
    mesh.touch_tet(3);
    const TetVertices v = mesh.tet(5);
    mesh.set_tet_vertices(5, v);
    CHECK(mesh.changed_since(3, e));
    CHECK(mesh.changed_since(5, e));
    CHECK_FALSE(mesh.changed_since(4, e));
    std::size_t changed = 0;
    mesh.compact();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) changed += mesh.changed_since(t, e);
    CHECK(changed == 2);
    const auto marks = changed_vertices(mesh, e);
    CHECK(std::count(marks.begin(), marks.end(), 1) >= 4);
  }

  TEST_CASE("the quality cache forgets a tet when it is written or touched") {
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    set_uniform_metric(mesh, 1.0);
    CHECK(mesh.cached_quality(0) == Mesh::kUnknownQuality);
    const double q = cached_mean_ratio<LogEuclidean>(mesh, 0);
    CHECK(mesh.cached_quality(0) == q);
    mesh.touch_tet(0);
    CHECK(mesh.cached_quality(0) == Mesh::kUnknownQuality);
    cached_mean_ratio<LogEuclidean>(mesh, 0);
    set_uniform_metric(mesh, 2.0);  // a new metric field clears it all
    CHECK(mesh.cached_quality(0) == Mesh::kUnknownQuality);
  }
}

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("passes restricted to what changed find nothing on an unchanged mesh - caches stay fresh", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using C = typename T::Concurrency;
    Mesh mesh = jittered_box(3, 0.35, 7);
    set_uniform_metric(mesh, 0.3);
    // Flips until nothing changes, then once more from the last start.
    ReconnectOptions flips;
    for (int i = 0; i < 20; ++i) {
      const Mesh::Epoch start = mesh.next_epoch();
      const auto st = reconnect<S, C, MinQuality>(mesh, flips);
      flips.scope.changed_since = start;
      CHECK(require_cache_fresh<S>(mesh) > 0);
      if (st.applied == 0) break;
    }
    const Mesh::Epoch start = mesh.next_epoch();
    CHECK(reconnect<S, C, MinQuality>(mesh, flips).tried == 0);
    flips.scope.changed_since = start;
    CHECK(reconnect<S, C, MinQuality>(mesh, flips).tried == 0);
    // Smoothing: moves touch the balls; after a pass with no move, nothing
    // is left to try. (A pass may touch every tet: the cache may be empty
    // after one pass, not after all.)
    SmoothOptions smooth{.below = 1.0};
    std::size_t cached = 0;
    for (int i = 0; i < 50; ++i) {
      const Mesh::Epoch s0 = mesh.next_epoch();
      const auto st = smooth_vertices<S, C>(mesh, smooth);
      smooth.scope.changed_since = s0;
      cached += require_cache_fresh<S>(mesh);
      if (st.applied == 0) break;
    }
    CHECK(cached > 0);
    CHECK(smooth_vertices<S, C>(mesh, smooth).tried == 0);
    require_valid(mesh, 1.0);
  }

  TEST_CASE("an adaptation leaves every cached quality equal to a fresh computation") {
    Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    set_uniform_metric(mesh, 0.2);
    AdaptOptions o;
    o.max_cycles = 4;
    o.quality_passes = 1;
    adapt<LogEuclidean, Filtered, Serial>(mesh, o);
    const std::string fresh = report_csv(quality_report(mesh, "log-euclidean"));
    CHECK(require_cache_fresh<LogEuclidean>(mesh) > 0);
    require_valid(mesh, 1.0);
    // So the report after adapt may read the cache (the CLI's does).
    CHECK(report_csv(quality_report(mesh, "log-euclidean", {.cached_quality = true})) == fresh);
  }
}
