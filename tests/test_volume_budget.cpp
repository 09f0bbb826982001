// Curved boundaries without a model: a torus meshed by gmsh, and Mmg's
// torus with the metric that comes with it, adapted with their facets
// only (no model) under every policy. Each boundary collapse and each
// move of a boundary vertex takes its change of volume from the
// adaptation's budget: the run ends valid, the volume within the budget,
// and the budget's account equal to the volume's actual change.
#include "operator_test_support.hpp"

#include <metrica/geometry/bootstrap.hpp>
#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/pipeline/adapt.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace metrica;
using namespace metrica::test;

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("a curved faceted boundary: the collapses keep the volume within their budget", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using P = typename T::Precision;
    using C = typename T::Concurrency;
    const CadModel model(std::string(METRICA_TEST_DATA_DIR) + "/torus.geo");
    Mesh mesh = build_mesh(bootstrap_mesh(model, {.size = 0.09}));
    const double volume = mesh.volume();
    // The UGAWG linear metric, coarser: most of the surface coarsens.
    const MetricFunction metric = [](const Point& p) {
      Sym6 m = evaluate(AnalyticMetric::linear, p);
      for (double& x : m) x /= 1.5 * 1.5;
      return m;
    };
    set_metric_function(mesh, metric);
    AdaptOptions o;
    o.max_cycles = 3;
    o.repair_rounds = 2;
    shorten_when_slow<P>(o);
    Adapter<S, C> a(mesh, &metric);
    a.set_volume_budget(o.volume_budget);
    run_pipeline(a, standard_pipeline<Adapter<S, C>>(o));
    const auto report = mesh.validate();
    INFO(report.to_string());
    REQUIRE(report.ok());
    const double change = mesh.volume() - volume;
    CHECK(std::abs(change) <= o.volume_budget * volume * (1.0 + 1e-9));
    // The account is the collapses' and the moves'; flips change the
    // boundary only where it is flat to 1e-9 (1 - cos).
    CHECK(std::abs(change - a.volume_budget().total()) <= 1e-10 * volume);
    CHECK(a.volume_budget().total() != 0.0);  // the surface did coarsen
  }

  TEST_CASE_TEMPLATE("Mmg's torus with its metric: the budget holds every change of volume", T,
                     METRICA_POLICY_COMBINATIONS) {
    // Mmg's io_multisols example (tests/data/mmg/README.md). Its metric
    // spends the whole budget: on two threads, ridge vertices moved along
    // straight ridges between curved faces used to take the volume past it.
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using P = typename T::Precision;
    using C = typename T::Concurrency;
    const std::string dir = std::string(METRICA_TEST_DATA_DIR) + "/mmg/";
    Mesh mesh = build_mesh(io::read_mesh_file(dir + "torus.mesh"));
    const auto metric = metric_field_from_sol(io::read_sol(dir + "torus.sol"), mesh.num_vertices(), "torus.sol");
    assign_metric(mesh, metric);
    const double volume = mesh.volume();
    const BackgroundMetric background(mesh);
    using A = Adapter<S, C>;
    A a(mesh, &background);
    Pipeline<A> p = standard_pipeline<A>(AdaptOptions{});
    p.max_cycles = 6;
    p.repair_rounds = 2;
    shorten_when_slow<P>(p);
    run_pipeline(a, p);
    const auto report = mesh.validate();
    INFO(report.to_string());
    REQUIRE(report.ok());
    const double change = mesh.volume() - volume;
    CHECK(std::abs(change) <= AdaptOptions{}.volume_budget * volume * (1.0 + 1e-9));
    CHECK(std::abs(change - a.volume_budget().total()) <= 1e-10 * volume);
    CHECK(a.volume_budget().total() != 0.0);
  }
}
