// The registry of stage kinds (pipeline/stage_registry.hpp):
//   - every kind makes a stage that runs, under its name;
//   - values are checked against their options (kind, range, whole
//     numbers), unknown options and operations are refused by name;
//   - a pipeline made from the registry runs as the same pipeline made by
//     hand (the same mesh, serially).
#include "operator_test_support.hpp"

#include <metrica/pipeline/stage_registry.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace metrica;
using namespace metrica::test;

namespace {
using A = Adapter<LogEuclidean, Serial>;

std::string refusal(const std::string& op, const StageValues& values) {
  try {
    make_stage<A>("s", op, values);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}
}  // namespace

TEST_SUITE("invariant") {
  TEST_CASE("every kind of stage makes a stage that runs under its name") {
    for (const auto& kind : stage_kinds<A>()) {
      CAPTURE(kind.op);
      Mesh mesh = small_linear_box();
      const MetricFunction metric = small_linear;
      A adapter(mesh, &metric);
      const Stage<A> stage = make_stage<A>("my-" + std::string(kind.op), kind.op, {});
      CHECK(stage.name == "my-" + std::string(kind.op));
      stage.run(adapter);
      require_valid(mesh, 1.0);
    }
  }

  TEST_CASE("values are checked against their options; unknown options and operations are refused by name") {
    CHECK(refusal("flip", {{"seed_below", 0.5}, {"max_sweeps", 3.0}, {"face_flips", false}}).empty());
    CHECK(refusal("flip", {{"criterion", std::string("metric-delaunay")}}).empty());
    CHECK(refusal("flip", {{"seed_below", 1.5}}) == "stage 's': seed_below must be a number in [0, 1]");
    CHECK(refusal("flip", {{"max_sweeps", 2.5}}) == "stage 's': max_sweeps must be a whole number in [1, 1000]");
    CHECK(refusal("flip", {{"face_flips", 1.0}}) == "stage 's': face_flips must be true or false");
    CHECK(refusal("flip", {{"criterion", std::string("delaunay")}}).find("unknown criterion of stage 's'") == 0);
    CHECK(refusal("collapse", {{"below", 0.5}}) ==
          "stage 's' (collapse): unknown option 'below' (min_length, max_new_length, shape_floor)");
    CHECK(refusal("swap", {{"below", 0.5}}) == "stage 's' (swap): unknown option 'below' (none)");
    CHECK(refusal("refine", {}) ==
          "stage 's': unknown operation 'refine' (collapse, split, centroids, flip, smooth, swap)");
  }

  TEST_CASE("a pipeline made from the registry runs as the same pipeline made by hand") {
    const MetricFunction metric = small_linear;
    auto run = [&](bool registry) {
      Mesh mesh = small_linear_box();
      A adapter(mesh, &metric);
      Pipeline<A> p;
      p.max_cycles = 4;
      p.quality_passes = 1;
      p.repair_rounds = 0;
      if (registry) {
        p.cycle = {make_stage<A>("collapse", "collapse", {}), make_stage<A>("split", "split", {}),
                   make_stage<A>("flip", "flip", {{"seed_below", 0.8}}), make_stage<A>("smooth", "smooth", {})};
        p.polish = {make_stage<A>("smooth", "smooth", {{"below", 1.0}})};
      } else {
        ReconnectOptions r;
        r.seed_below = 0.8;
        SmoothOptions all;
        all.below = 1.0;
        p.cycle = {{"collapse", [](A& a) { return a.collapse({}); }},
                   {"split", [](A& a) { return a.split({}); }},
                   {"flip", [r](A& a) { return a.flips<MinQuality>(r, "flip"); }},
                   {"smooth", [](A& a) { return a.smooth({}, "smooth"); }}};
        p.polish = {{"smooth", [all](A& a) { return a.smooth(all, "smooth"); }}};
      }
      run_pipeline(adapter, p);
      return sorted_tets(mesh);
    };
    CHECK(run(true) == run(false));
  }
}
