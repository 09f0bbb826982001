// The operation protocol and the pass runner:
//   - each operation's decide, property-tested without applying
//     (check_plans, operators/testing.hpp): a plan
//     never inverts a tet and never drops below the shape floor; applied on
//     a copy, it keeps the mesh valid, the boundary areas per surface id and
//     the ridges;
//   - Acceptance (the shape floor and the criterion's bar) and the shape
//     floor of 2-3 flips under every criterion;
//   - a toy executor (items in reverse order) adapts a box with no
//     operator edited.
#include "laplacian_move.hpp"  // examples/operation: the tutorial's operation
#include "operator_test_support.hpp"

#include <metrica/mesh_build.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/pipeline/adapt.hpp>

#include <doctest/doctest.h>

#include <limits>
#include <string>
#include <vector>

using namespace metrica;
using namespace metrica::test;

namespace {

// check_plans (operators/testing.hpp) with its finding reported; the
// number of plans.
template <class S, Operation Op>
int plans_checked(const Mesh& mesh, const Op& op, const std::vector<typename Op::Item>& items, double floor) {
  const PlanCheck r = check_plans<S>(mesh, op, std::span<const typename Op::Item>(items), floor);
  INFO(r.problem);
  CHECK(r.ok());
  return r.plans;
}

template <class S>
std::vector<EdgeSeed> all_edge_seeds(const Mesh& mesh) {
  std::vector<TetId> tets;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t)
    if (mesh.tet_alive(t)) tets.push_back(t);
  MeshArray<EdgeSeed> seeds;
  unique_edge_seeds(
      std::span<const TetId>(tets), [&](TetId t) -> const TetVertices& { return mesh.tet(t); }, mesh.vertex_capacity(),
      seeds);
  return {seeds.begin(), seeds.end()};
}

// The plans' properties and the toy executor, which run no threads, are
// not in the ThreadSanitizer build: neither are their helpers.
#if !METRICA_TSAN
std::vector<TetId> all_tets(const Mesh& mesh) {
  std::vector<TetId> out;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t)
    if (mesh.tet_alive(t)) out.push_back(t);
  return out;
}

// A scored criterion that prefers any new configuration (old tets score 0,
// new ones 1): only the shape floor can refuse under it.
struct PreferNew {
  static constexpr std::string_view name = "prefer-new";
  static constexpr bool measures_shape = false;
  template <MetricSpace S>
  static double tet_score(const Mesh&, const TetVertices&) {
    return 1.0;
  }
  template <MetricSpace S>
  static double tet_score_at(const Mesh&, const TetVertices&, const TetPoints&) {
    return 1.0;
  }
  template <MetricSpace S>
  static double tet_score_of(const Mesh&, TetId) {
    return 0.0;
  }
  static double score_in(const TetPoints&, const Sym6&) { return 1.0; }
  static double bar(double reference) { return reference; }
};

// Two tets on face pqr whose apexes' segment crosses the face 1e-5 from
// edge pq: the 2-3 flip's tet (p, q, a, b) is a sliver (Q ~ 5e-4), the
// old tets are fair.
Mesh sliver_pair() {
  io::MeshData d;
  d.vertices = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(0.5, 1e-5, 1), Point(0.5, 1e-5, -1)};
  d.tets = {TetVertices{0, 1, 2, 3}, TetVertices{1, 0, 2, 4}};
  return build_mesh(d);
}

// Serial with the items of every work list run in reverse order: an
// executor that is not one of the library's.
struct ReverseSerial : Serial {
  static constexpr std::string_view name = "reverse";
  template <class Item, class Work>
  static PassTally for_each(Mesh&, std::span<const Item> items, const PassRoom&, Work&& work) {
    Locks locks;
    PassTally tally;
    tally.rounds = items.empty() ? 0 : 1;
    for (std::size_t i = items.size(); i-- > 0;) work(items[i], 0, locks);
    return tally;
  }
};
static_assert(Concurrency<ReverseSerial>);
#endif  // !METRICA_TSAN

template <class S, class P>
struct SpacePrecision {
  using Space = S;
  using Precision = P;
};

}  // namespace

#if METRICA_DEFAULT_POLICIES_ONLY
#define METRICA_SPACE_PRECISION SpacePrecision<LogEuclidean, Filtered>
#else
#define METRICA_SPACE_PRECISION \
  SpacePrecision<LogEuclidean, Filtered>, SpacePrecision<Anisotropic, Exact>, SpacePrecision<Isotropic, Fast>
#endif

#if !METRICA_TSAN
TEST_SUITE("property") {
  TEST_CASE_TEMPLATE("a decided split or centroid insertion never inverts - applied it keeps areas and ridges", T,
                     METRICA_SPACE_PRECISION) {
    using S = typename T::Space;
    Mesh mesh = jittered_box(3, 0.3, 11);
    require_valid(mesh, 1.0);
    set_uniform_metric(mesh, 0.12);
    const auto long_edges = edges_beyond<S>(mesh, kUnitBand.hi, EdgeOrder::longest_first);
    CHECK(plans_checked<S>(mesh, EdgeSplit<S>{{}, mesh.next_epoch()}, long_edges, 0.0) > 0);
    // With a shape floor (children measured in their parent's metric).
    CHECK(plans_checked<S>(mesh, EdgeSplit<S>{{.shape_floor = 0.2}, mesh.next_epoch()}, long_edges, 0.0) > 0);
    std::vector<std::uint32_t> of_tet;
    const auto candidates = centroid_candidates<S>(mesh, {}, of_tet);
    CHECK(plans_checked<S>(mesh, CentroidInsertion<S>{{}, mesh.next_epoch()}, candidates, 0.0) > 0);
  }

  TEST_CASE("a plan is applied only with its scratch as decided: after another seed or decide it is refused") {
    using S = LogEuclidean;
    Mesh mesh = jittered_box(3, 0.3, 11);
    set_uniform_metric(mesh, 0.12);
    const auto long_edges = edges_beyond<S>(mesh, kUnitBand.hi, EdgeOrder::longest_first);
    REQUIRE(long_edges.size() >= 2);
    const EdgeSplit<S> split{{}, mesh.next_epoch()};
    EdgeSplitScratch s;
    const auto first = decide_item(mesh, split, long_edges[0], s);
    REQUIRE(first);
    const auto second = decide_item(mesh, split, long_edges[1], s);
    REQUIRE(second);
    Mesh copy = mesh;
    PlannedTets planned;
    CHECK_THROWS_AS(apply_plan(copy, split, long_edges[0], first, s), std::logic_error);
    CHECK_THROWS_AS(preview_plan(mesh, split, long_edges[0], first, s, planned), std::logic_error);
    CHECK_THROWS_AS(apply_plan(copy, split, long_edges[0], Decision<EdgeSplitPlan>(Refusal::rejected), s),
                    std::logic_error);
    CHECK(copy.num_vertices() == mesh.num_vertices());
    apply_plan(copy, split, long_edges[1], second, s);
    CHECK(copy.num_vertices() == mesh.num_vertices() + 1);
    require_valid(copy, 1.0);
  }

  TEST_CASE_TEMPLATE("a decided collapse never inverts nor drops below its floor - applied it keeps areas and ridges",
                     T, METRICA_SPACE_PRECISION) {
    using S = typename T::Space;
    Mesh mesh = jittered_box(4, 0.3, 12);
    require_valid(mesh, 1.0);
    set_uniform_metric(mesh, 0.5);
    const auto short_edges = edges_beyond<S>(mesh, kUnitBand.lo, EdgeOrder::shortest_first);
    const CollapseOptions o;
    CHECK(plans_checked<S>(mesh, Collapse<S>{o}, short_edges, o.shape_floor) > 0);
    CHECK(plans_checked<S>(mesh, Collapse<S, MinQuality>{o}, short_edges, o.shape_floor) > 0);
  }

  TEST_CASE_TEMPLATE("decided flips and smoothing moves never invert nor drop below the floor under every criterion", T,
                     METRICA_SPACE_PRECISION) {
    using S = typename T::Space;
    using P = typename T::Precision;
    Mesh mesh = jittered_box(3, 0.35, 3);
    require_valid(mesh, 1.0);
    set_uniform_metric(mesh, 0.3);
    const FlipOptions fo;
    const auto edges = all_edge_seeds<S>(mesh);
    const auto tets = all_tets(mesh);
    CHECK(plans_checked<S>(mesh, EdgeRemoval<S, MinQuality>{fo}, edges, fo.shape_floor) > 0);
    CHECK(plans_checked<S>(mesh, EdgeRemoval<S, MaxMinEdgeWeight>{fo}, edges, fo.shape_floor) > 0);
    plans_checked<S>(mesh, EdgeRemoval<S, MetricDelaunay<P>>{fo}, edges, fo.shape_floor);
    plans_checked<S>(mesh, EdgeRemoval<S, PreferNew>{fo}, edges, fo.shape_floor);
    CHECK(plans_checked<S>(mesh, FaceFlip<S, MinQuality>{fo}, tets, fo.shape_floor) > 0);
    plans_checked<S>(mesh, FaceFlip<S, MaxMinEdgeWeight>{fo}, tets, fo.shape_floor);
    plans_checked<S>(mesh, FaceFlip<S, MetricDelaunay<P>>{fo}, tets, fo.shape_floor);
    CHECK(plans_checked<S>(mesh, FaceFlip<S, PreferNew>{fo}, tets, fo.shape_floor) > 0);
    const auto vertices = all_vertices(mesh);
    const SmoothOptions so{.below = 1.0};
    CHECK(plans_checked<S>(mesh, Smoothing<S>{{}, so}, vertices, 0.0) > 0);
    CHECK(plans_checked<S>(mesh, Smoothing<S, MaxMinEdgeWeight>{{}, so}, vertices, so.shape_floor) > 0);
  }

  TEST_CASE_TEMPLATE("the 2-3 flip keeps the shape floor under every criterion", T, METRICA_SPACE_PRECISION) {
    using S = typename T::Space;
    using P = typename T::Precision;
    Mesh mesh = sliver_pair();
    set_uniform_metric(mesh, 1.0);
    REQUIRE(mesh.num_tets() == 2);
    const TetId t = local_index(mesh.tet(0), 3) >= 0 ? 0 : 1;
    const int face = local_index(mesh.tet(t), 3);
    FlipScratch s;
    const FlipOptions fo;
    // Without the floor, PreferNew takes the flip: the candidate holds the sliver.
    const double old_worst = worst_quality<S>(mesh);
    CHECK(old_worst > 0.3);
    auto check_floor = [&](const auto& d) {
      if (!d) return;
      for (const auto& c : s.candidate) CHECK(S::mean_ratio(mesh, c) >= std::min(fo.shape_floor, old_worst));
    };
    const auto prefer_new = decide_flip23<S, PreferNew>(mesh, t, face, s, fo);
    double sliver = 1.0;
    for (const auto& c : s.candidate) sliver = std::min(sliver, S::mean_ratio(mesh, c));
    CHECK(sliver < fo.shape_floor);  // the configuration holds the case
    CHECK_FALSE(prefer_new);
    check_floor(decide_flip23<S, MinQuality>(mesh, t, face, s, fo));
    check_floor(decide_flip23<S, MaxMinEdgeWeight>(mesh, t, face, s, fo));
    check_floor(decide_flip23<S, MetricDelaunay<P>>(mesh, t, face, s, fo));
    check_floor(decide_flip23<S, AlwaysFlip>(mesh, t, face, s, fo));
    // With the floor at 0 the flip is taken (the floor is what refused it).
    FlipOptions no_floor = fo;
    no_floor.shape_floor = 0.0;
    CHECK(static_cast<bool>(decide_flip23<S, PreferNew>(mesh, t, face, s, no_floor)));
  }
}

TEST_SUITE("property") {
  TEST_CASE_TEMPLATE("Acceptance: the floor unless an old tet was worse, implied by a shape criterion, 0 asks nothing",
                     T, METRICA_SPACE_PRECISION) {
    using S = typename T::Space;
    Mesh mesh = sliver_pair();
    set_uniform_metric(mesh, 1.0);
    const std::array<TetId, 1> old{0};
    const double q_old = S::mean_ratio(mesh, mesh.tet(0));
    const TetPoints x = detail::tet_points(mesh, mesh.tet(0));
    for (const double q : {0.5 * q_old, 0.999 * q_old, q_old, 1.001 * q_old}) {
      // Below the floor: admitted only when not worse than the old tet.
      auto r = Acceptance<S, ShapeOnly>(2.0 * q_old).replacing(mesh, old);
      CHECK(r.shape_admits(q) == (q >= q_old));
      // Above the floor: admitted.
      CHECK(Acceptance<S, ShapeOnly>(0.25 * q_old).replacing(mesh, old).shape_admits(q));
      // A floor of 0, or a criterion that measures shape: the floor asks nothing.
      CHECK(Acceptance<S, ShapeOnly>(0.0).replacing(mesh, old).shape_admits(q));
      CHECK(Acceptance<S, MinQuality>(2.0 * q_old).replacing(mesh, old).shape_admits(q));
    }
    CHECK_FALSE(Acceptance<S, ShapeOnly>(0.0).decides());
    CHECK(Acceptance<S, ShapeOnly>(0.1).decides());
    CHECK(Acceptance<S, MinQuality>(0.0).decides());
    // The criterion's bar: the old tet does not beat itself under a strict
    // criterion; an indifferent one takes it.
    CHECK_FALSE(Acceptance<S, MinQuality>(0.0).replacing(mesh, old).beats(mesh.tet(0), x));
    CHECK(Acceptance<S, ShapeOnly>(0.0).replacing(mesh, old).beats(mesh.tet(0), x));
    // keeps_shape over the mesh's tets: the sliver pair's worse tet against the better one.
    const TetId worse = S::mean_ratio(mesh, mesh.tet(0)) < S::mean_ratio(mesh, mesh.tet(1)) ? 0 : 1;
    const std::array<TetId, 1> better{1 - worse};
    const std::array<TetVertices, 1> candidate{mesh.tet(worse)};
    const double q_worse = S::mean_ratio(mesh, mesh.tet(worse));
    CHECK(Acceptance<S, ShapeOnly>(0.5 * q_worse).keeps_shape(mesh, better, candidate));
    CHECK(Acceptance<S, ShapeOnly>(2.0 * q_worse).keeps_shape(mesh, better, candidate) ==
          (q_worse >= S::mean_ratio(mesh, mesh.tet(1 - worse))));
  }
}

TEST_SUITE("invariant") {
  TEST_CASE("a toy executor (items in reverse order) adapts a box validly with no operator edited") {
    Mesh mesh = small_linear_box();
    const MetricFunction metric = small_linear;
    const AdaptReport r = adapt<LogEuclidean, Filtered, ReverseSerial>(mesh, AdaptOptions{}, {.metric = &metric});
    require_valid(mesh, 1.0);
    const CycleReport& last = r.cycles.back();
    INFO("in range " << last.conformity << ", min Q " << last.min_quality);
    CHECK(r.ops.get("split").applied > 0);
    CHECK(r.ops.get("collapse").applied > 0);
    CHECK(last.conformity > 0.85);
    CHECK(last.min_quality > 0.2);
  }
}
#endif  // !METRICA_TSAN

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE(
      "the tutorial's operation (examples/operation) keeps the mesh valid and never lowers the worst tet", T,
      METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using C = typename T::Concurrency;
    Mesh mesh = jittered_box(4, 0.3, 21);
    set_uniform_metric(mesh, 0.3);
    const example::LaplacianMove<S> op;
    // Its plans, property-tested without applying them.
    CHECK(plans_checked<S>(mesh, op, all_vertices(mesh), 0.0) > 0);
    const double before = worst_quality<S>(mesh);
    const OperatorStats stats = run_pass<C>(mesh, op, all_vertices(mesh));
    CHECK(stats.applied > 0);
    require_valid(mesh, 1.0);
    CHECK(worst_quality<S>(mesh) >= before);
  }
}

// docs/writing-an-operator.md, step 3, as written there: the public
// testing tools under PolicyCombinations.
TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE_DEFINE("a Laplacian move never inverts under every policy (the tutorial's test)", T, laplacian) {
    using S = typename T::Space;
    const ExecutorOf<T> executor;
    std::mt19937_64 rng(7);
    Mesh mesh = jittered_box(4, 0.3, rng);
    set_uniform_metric(mesh, 0.3);
    std::vector<VertexId> vertices;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) vertices.push_back(v);
    const PlanCheck plans = check_plans<S>(mesh, example::LaplacianMove<S>{}, std::span<const VertexId>(vertices), 0.0);
    INFO(plans.problem);
    CHECK(plans.ok());
    CHECK(plans.plans > 0);
    run_pass<typename T::Concurrency>(mesh, example::LaplacianMove<S>{}, vertices);
    CHECK(mesh.validate().ok());
  }
  TEST_CASE_TEMPLATE_APPLY(laplacian, PolicyCombinations);
}
