// A pipeline composed by name (pipeline/composed_pipeline.hpp):
//   - the command line's stage lists parse into names, operations and
//     typed values, and malformed lists are refused naming the list;
//   - the rules are the settings table's first rows, read by their names;
//   - run_composed runs as the same pipeline made from the registry by
//     hand (the same mesh, serially) and ends valid under every
//     concurrency;
//   - unknown stages, options and concurrencies are refused.
#include "operator_test_support.hpp"

#include <metrica/pipeline/composed_pipeline.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace metrica;
using namespace metrica::test;

namespace {

std::string refusal(auto&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

ComposedPipeline short_pipeline() {
  ComposedPipeline p;
  p.cycle = parse_stage_list("collapse, split, flip:seed_below=0.8, smooth", "--cycle");
  p.polish = parse_stage_list("smooth:below=1", "--polish");
  p.rules.max_cycles = 4;
  p.rules.quality_passes = 1;
  p.rules.repair_rounds = 0;
  return p;
}

}  // namespace

TEST_SUITE("invariant") {
  TEST_CASE("a stage list parses into names, operations and typed values") {
    const auto list = parse_stage_list(
        " collapse ,delaunay=flip:criterion=metric-delaunay:face_flips=true:max_sweeps=3,smooth:below=0.5", "--cycle");
    REQUIRE(list.size() == 3);
    CHECK(list[0].name == "collapse");
    CHECK(list[0].op == "collapse");
    CHECK(list[0].values.empty());
    CHECK(list[1].name == "delaunay");
    CHECK(list[1].op == "flip");
    CHECK(std::get<std::string>(list[1].values.at("criterion")) == "metric-delaunay");
    CHECK(std::get<bool>(list[1].values.at("face_flips")));
    CHECK(std::get<double>(list[1].values.at("max_sweeps")) == 3.0);
    CHECK(std::get<double>(list[2].values.at("below")) == 0.5);
    CHECK(parse_stage_list("  ", "--polish").empty());
  }

  TEST_CASE("malformed stage lists are refused naming the list and the stage") {
    CHECK(refusal([] { parse_stage_list("collapse,,split", "--cycle"); }) ==
          "--cycle: an empty stage in 'collapse,,split'");
    CHECK(refusal([] { parse_stage_list("flip:seed_below", "--cycle"); }) ==
          "--cycle: stage 'flip:seed_below': 'seed_below' is not OPTION=VALUE (a stage is "
          "[NAME=]OP[:OPTION=VALUE]...)");
    CHECK(refusal([] { parse_stage_list("=flip", "--polish"); }).find("an empty name before '='") != std::string::npos);
    CHECK(refusal([] { parse_stage_list("name=:below=1", "--polish"); }).find("no operation") != std::string::npos);
    CHECK(refusal([] { parse_stage_list("smooth:below=1:below=2", "--repair"); }).find("option 'below' given twice") !=
          std::string::npos);
    // The registry's checks, before anything runs.
    ComposedPipeline p;
    p.cycle = parse_stage_list("flip:seed_below=2", "--cycle");
    CHECK(refusal([&] { check_composed(p); }) == "stage 'flip': seed_below must be a number in [0, 1]");
    p.cycle = parse_stage_list("flip:criterion=0.5", "--cycle");
    CHECK(refusal([&] { check_composed(p); }).find("criterion must be min-quality") != std::string::npos);
    p.cycle = parse_stage_list("collapse,collapse", "--cycle");
    CHECK(refusal([&] { check_composed(p); }).find("two stages named 'collapse'") == 0);
    p.cycle = parse_stage_list("refine", "--cycle");
    CHECK(refusal([&] { check_composed(p); }).find("unknown operation 'refine'") != std::string::npos);
    CHECK(refusal([] { check_composed({}); }) == "pipeline: no stage to run");
  }

  TEST_CASE("the rules are the settings table's first rows") {
    std::vector<std::string> names;
    for (const AdaptSetting& s : pipeline_rule_settings()) names.emplace_back(s.name);
    CHECK(names == std::vector<std::string>{"cycles", "quality-passes", "repair-rounds", "repair-below", "min-change",
                                            "min-conformity-gain", "near-unit-conformity"});
    AdaptOptions o;
    const auto set = [&](std::string_view name, double x) { adapt_setting(name)->set(o, x); };
    set("cycles", 3);
    set("min_change", 0.01);
    set("near-unit-conformity", 0.8);
    const PipelineRules& r = o;
    CHECK(r.max_cycles == 3);
    CHECK(r.min_change == 0.01);
    CHECK(r.near_unit_conformity == 0.8);
    CHECK(!adapt_setting("cycles")->accepts(2.5));
    CHECK(!adapt_setting("min-conformity-gain")->accepts(1.5));
  }

  TEST_CASE("run_composed runs as the pipeline made from the registry by hand") {
    using A = Adapter<LogEuclidean, Serial>;
    const MetricFunction metric = small_linear;
    const ComposedPipeline spec = short_pipeline();
    Mesh composed = small_linear_box();
    AdaptInputs inputs;
    inputs.metric = &metric;
    run_composed(composed, spec, inputs, "serial");

    Mesh by_hand = small_linear_box();
    A adapter(by_hand, &metric);
    adapter.set_volume_budget(AdaptOptions{}.volume_budget);
    Pipeline<A> p;
    p.max_cycles = 4;
    p.quality_passes = 1;
    p.repair_rounds = 0;
    p.cycle = {make_stage<A>("collapse", "collapse", {}), make_stage<A>("split", "split", {}),
               make_stage<A>("flip", "flip", {{"seed_below", 0.8}}), make_stage<A>("smooth", "smooth", {})};
    p.polish = {make_stage<A>("smooth", "smooth", {{"below", 1.0}})};
    run_pipeline(adapter, p);
    CHECK(sorted_tets(composed) == sorted_tets(by_hand));
  }

  TEST_CASE("run_composed ends valid under every concurrency") {
    const MetricFunction metric = small_linear;
    for (const char* concurrency : {"serial", "speculative"}) {
      CAPTURE(concurrency);
      Mesh mesh = small_linear_box();
      const double volume = mesh.volume();
      AdaptInputs inputs;
      inputs.metric = &metric;
      int cycles = 0;
      inputs.on_cycle = [&](const CycleReport&) { ++cycles; };
      const AdaptReport report = run_composed(mesh, short_pipeline(), inputs, concurrency);
      require_valid(mesh, volume);
      CHECK(cycles >= 2);
      CHECK(report.ops.get("split").applied > 0);
    }
  }

  TEST_CASE("an unknown concurrency is refused") {
    Mesh mesh = small_linear_box();
    const MetricFunction metric = small_linear;
    AdaptInputs inputs;
    inputs.metric = &metric;
    CHECK(refusal([&] { run_composed(mesh, short_pipeline(), inputs, "gpu"); }) ==
          "unknown concurrency 'gpu' (speculative, serial)");
  }
}
