// The pipeline object and the pass runner of pipelines:
//   - custom pipelines (stages reordered, one replaced) report by stage
//     name, and a stage's name is the key of its passes' epoch;
//   - the cycles stop for the stated reason (the mesh's own vertex
//     changes), whatever the stages are called;
//   - Adapter::run binds the adapter's metric and geometry;
//   - only the last quality pass measures the share of edges in range.
#include "operator_test_support.hpp"

#include <metrica/pipeline/adapt.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace metrica;
using namespace metrica::test;

namespace {

// The standard pipeline with every stage of the cycles renamed.
template <class A>
Pipeline<A> renamed_cycle(const AdaptOptions& o) {
  Pipeline<A> p = standard_pipeline<A>(o);
  for (Stage<A>& s : p.cycle) s.name = "my-" + s.name;
  return p;
}

}  // namespace

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("a custom pipeline (stages reordered and one replaced) reports by stage name", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using A = Adapter<typename T::Space, typename T::Concurrency>;
    Mesh mesh = small_linear_box();
    const MetricFunction metric = small_linear;
    A adapter(mesh, &metric);
    Pipeline<A> p = standard_pipeline<A>(AdaptOptions{});
    p.max_cycles = 6;
    shorten_when_slow<typename T::Precision>(p);
    // Split before collapse, metric Delaunay flips under a key of their
    // own, and smoothing replaced by a stage of our own that runs the
    // smoothing operation over every vertex. (A criterion of no standard
    // stage, such as MaxMinEdgeWeight, compiles in the program that uses
    // it: examples/compose and examples/consumer do.)
    int custom_runs = 0;
    p.cycle = {{"split", [](A& a) { return a.split({}); }},
               {"collapse", [](A& a) { return a.collapse({}); }},
               {"delaunay-cycle", [](A& a) { return a.template flips<MetricDelaunay<typename T::Precision>>({}); }},
               {"my-smooth", [&custom_runs](A& a) {
                  ++custom_runs;
                  const std::vector<VertexId> vertices = all_vertices(a.mesh());
                  return a.run(Smoothing<typename A::Space>{{}, {.below = 1.0}}, std::span<const VertexId>(vertices));
                }}};
    const AdaptReport& r = run_pipeline(adapter, p);
    require_valid(mesh, 1.0);
    CHECK(custom_runs > 0);
    CHECK(r.ops.get("my-smooth").applied > 0);
    CHECK(r.ops.get("split").applied > 0);
    CHECK(r.ops.get("smooth").tried > 0);  // the standard quality phase
    CHECK(r.cycles.front().ops.begin()->first == "split");
    // Under ThreadSanitizer the run is cut to two cycles and one repair
    // round (shorten_when_slow), and on 8 threads its worst tet depends on
    // the schedule (0.066 once): valid is what such a run promises.
    CHECK(r.cycles.back().min_quality > (kUnderThreadSanitizer ? 0.0 : 0.1));
    CHECK(adapter.since("delaunay-cycle") > 0);
  }

  TEST_CASE("renamed stages: the cycles stop for the same reason, after the same number of cycles") {
    using A = Adapter<LogEuclidean, Serial>;
    const MetricFunction metric = small_linear;
    auto run = [&](bool renamed) {
      Mesh mesh = small_linear_box();
      A adapter(mesh, &metric);
      AdaptOptions o;
      o.quality_passes = 0;
      o.repair_rounds = 0;
      const AdaptReport r = run_pipeline(adapter, renamed ? renamed_cycle<A>(o) : standard_pipeline<A>(o));
      return std::pair{r.cycles.size(), mesh.num_tets()};
    };
    const auto [standard_cycles, standard_tets] = run(false);
    const auto [renamed_cycles, renamed_tets] = run(true);
    CHECK(standard_cycles > 2);
    CHECK(renamed_cycles == standard_cycles);
    CHECK(renamed_tets == standard_tets);
  }

  TEST_CASE("a cycle that creates and removes no vertex is the last one; one that does goes on") {
    using A = Adapter<LogEuclidean, Serial>;
    const MetricFunction metric = small_linear;
    Mesh mesh = small_linear_box();
    A adapter(mesh, &metric);
    Pipeline<A> p = standard_pipeline<A>(AdaptOptions{});
    p.quality_passes = 0;
    p.repair.clear();
    p.cycle = {{"reconnect", [](A& a) { return a.flips({}); }}, {"relax", [](A& a) { return a.smooth({}); }}};
    CHECK(run_pipeline(adapter, p).cycles.size() == 1);
    const std::uint64_t before = mesh.vertex_changes();
    p.cycle = {{"refine", [](A& a) { return a.split({}); }}};
    p.max_cycles = 3;
    A second(mesh, &metric);
    const AdaptReport& r = run_pipeline(second, p);
    CHECK(r.cycles.size() > 1);
    CHECK(mesh.vertex_changes() - before >= r.ops.get("refine").applied);
  }

  TEST_CASE("quality passes before the last do not measure the share in range; the figures are the mesh's") {
    using A = Adapter<LogEuclidean, Serial>;
    const MetricFunction metric = small_linear;
    Mesh mesh = small_linear_box();
    A adapter(mesh, &metric);
    AdaptOptions o;
    o.quality_passes = 3;
    o.repair_rounds = 0;
    const AdaptReport& r = run_pipeline(adapter, standard_pipeline<A>(o));
    std::vector<const CycleReport*> passes;
    for (const CycleReport& c : r.cycles) {
      if (c.quality_phase) {
        passes.push_back(&c);
      } else {
        CHECK(c.conformity_measured);
        CHECK(c.conformity > 0.0);
      }
    }
    REQUIRE(passes.size() == 3);
    for (int k = 0; k < 2; ++k) {
      CHECK_FALSE(passes[k]->conformity_measured);
      CHECK(std::isnan(passes[k]->conformity));
      CHECK(passes[k]->min_quality > 0.0);
      CHECK(passes[k]->min_quality <= 1.0);
    }
    // Each round ends compacted; the last pass closes the run, measured.
    const CycleReport& last = *passes[2];
    CHECK(last.conformity_measured);
    CHECK(mesh.num_tets() == mesh.tet_capacity());
    CHECK(last.tets == mesh.num_tets());
    double worst = 0.0;
    CHECK(last.conformity == doctest::Approx(conformity<LogEuclidean>(mesh, &worst)));
    CHECK(last.min_quality == doctest::Approx(worst));
    CHECK(worst_quality<LogEuclidean>(mesh) == doctest::Approx(worst));
    require_valid(mesh, 1.0);
  }

  TEST_CASE("stages of one name share their epoch; another name starts from everything") {
    using A = Adapter<LogEuclidean, Serial>;
    const MetricFunction metric = small_linear;
    Mesh mesh = small_linear_box();
    A adapter(mesh, &metric);
    CHECK(mesh.quality_cache_space() == LogEuclidean::name);  // the cache says whose mean ratios it holds
    const Stages<A> stages = {{"flip", [](A& a) { return a.flips({.seed_below = 1.0}); }},
                              {"flip", [](A& a) { return a.flips({.seed_below = 1.0}); }},
                              {"other", [](A& a) { return a.flips({.seed_below = 1.0}); }}};
    // Each stage records its start; the second "flip" sees only what the
    // first changed, "other" (never ran) every tet.
    std::vector<Mesh::Epoch> started;
    for (const Stage<A>& s : stages) {
      CHECK(adapter.since(s.name) <= mesh.epoch());
      adapter.run_stage(s.name, s.run);
      started.push_back(adapter.since(s.name));
      CHECK(adapter.stage().empty());
    }
    CHECK(started[1] > started[0]);
    CHECK(adapter.since("never-ran") == 0);
    adapter.restart_all(mesh.next_epoch());
    CHECK(adapter.since("never-ran") == mesh.epoch());
  }
}
