// The UGAWG analytic metrics: reproduce the reference .solb, sizes along
// the right axes, and clear errors for bad metric fields.
#include "test_support.hpp"

#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <doctest/doctest.h>

using namespace metrica;

TEST_SUITE("regression") {
  TEST_CASE("linear on cube-linear-00 reproduces the UGAWG .solb to 1e-12 relative") {
    const auto mesh = io::read_meshb(test::ugawg("cube-linear-00.meshb"));
    const auto reference = io::read_sol(test::ugawg("cube-linear-00.solb"));
    const auto field = analytic_metric_field(AnalyticMetric::linear, mesh.vertices);
    const auto ours = metric_field_to_sol(field);
    REQUIRE(ours.values.size() == reference.values.size());
    double worst = 0;
    for (std::size_t i = 0; i < ours.values.size(); ++i) {
      const double scale = std::max(std::abs(reference.values[i]), 1.0);
      worst = std::max(worst, std::abs(ours.values[i] - reference.values[i]) / scale);
    }
    CHECK(worst <= 1e-12);
  }
}

TEST_SUITE("unit") {
  TEST_CASE("polar metrics: h_r across the circle r = 0.5 and h_t and h_z = 0.1 for polar-1") {
    for (auto kind : {AnalyticMetric::polar1, AnalyticMetric::polar2}) {
      const double t = 0.7;
      const Point on(0.5 * std::cos(t), 0.5 * std::sin(t), 0.3);
      const auto m = evaluate(kind, on);
      const Eigen::Vector3d er(std::cos(t), std::sin(t), 0), et(-std::sin(t), std::cos(t), 0), ez(0, 0, 1);
      CHECK(1.0 / std::sqrt(metric_norm2(m, er)) == doctest::Approx(0.001));
      CHECK(1.0 / std::sqrt(metric_norm2(m, ez)) == doctest::Approx(0.1));
      CHECK(1.0 / std::sqrt(metric_norm2(m, et)) == doctest::Approx(kind == AnalyticMetric::polar1 ? 0.1 : 0.025));
    }
    // Far from the circle polar-2's tangential size is back to 0.1.
    const auto far = evaluate(AnalyticMetric::polar2, Point(1.0, 0.0, 0.0));
    CHECK(1.0 / std::sqrt(metric_norm2(far, Eigen::Vector3d(0, 1, 0))) == doctest::Approx(0.1));
    CHECK(is_spd(evaluate(AnalyticMetric::polar1, Point(0, 0, 0))));  // on the axis
  }

  TEST_CASE("names") {
    for (const auto& n : analytic_metric_names()) CHECK(to_string(analytic_metric_from_name(n)) == n);
    CHECK_THROWS_WITH_AS(analytic_metric_from_name("cubic"), doctest::Contains("known: linear"), InputError);
  }

  TEST_CASE("bad metric fields: wrong count - non-SPD - NaN - non-positive size") {
    io::SolData s;
    s.count = 2;
    s.types = {io::SolType::sym_matrix};
    s.values = {1, 0, 1, 0, 0, 1, 1, 0, 1, 0, 0, 1};
    CHECK(metric_field_from_sol(s, 2, "m.solb").size() == 2);
    CHECK_THROWS_WITH_AS(metric_field_from_sol(s, 3, "m.solb"), doctest::Contains("mesh has 3 vertices"), InputError);
    s.values[5] = -1;
    CHECK_THROWS_WITH_AS(metric_field_from_sol(s, 2, "m.solb"), doctest::Contains("vertex 1 is not positive definite"),
                         InputError);
    s.values[5] = 1;
    s.values[8] = std::nan("");
    CHECK_THROWS_WITH_AS(metric_field_from_sol(s, 2, "m.solb"), doctest::Contains("vertex 2 has a non-finite"),
                         InputError);
    io::SolData h;
    h.count = 2;
    h.types = {io::SolType::scalar};
    h.values = {0.5, 0.0};
    CHECK_THROWS_WITH_AS(metric_field_from_sol(h, 2, "h.sol"), doctest::Contains("size at vertex 2"), InputError);
    h.values[1] = 0.25;
    const auto iso = metric_field_from_sol(h, 2, "h.sol");
    CHECK(iso[1][0] == doctest::Approx(16.0));
  }

  TEST_CASE("assign_metric stores M and log M per vertex") {
    auto mesh = build_mesh(io::read_meshb(test::ugawg("cube-linear-00.meshb")));
    std::vector<Point> points;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) points.push_back(mesh.point(v));
    assign_metric(mesh, analytic_metric_field(AnalyticMetric::linear, points));
    REQUIRE(mesh.has_metric());
    CHECK(mesh.metric(0)[0] == doctest::Approx(100.0));
    CHECK(mesh.log_metric(0)[0] == doctest::Approx(std::log(100.0)));
    CHECK_THROWS_AS(assign_metric(mesh, {}), InputError);
  }
}
