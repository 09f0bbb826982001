// The verification study's parts: the degree-5 tet quadrature (exact on
// every monomial of degree <= 5), the L2 norm of the P1 interpolation error
// (zero for a linear field, second order under refinement), point location
// and field transfer between meshes (exact for linear fields), and a short
// adaptive loop whose error falls when the complexity doubles.
#include "operator_test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/interpolation_error.hpp>
#include <metrica/metrics/quadrature.hpp>
#include <metrica/pipeline/adaptive_loop.hpp>
#include <metrica/point_location.hpp>

#include <cmath>
#include <random>

using namespace metrica;
using namespace metrica::test;

namespace {

double factorial(int k) {
  double f = 1;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

// The rule on the reference tet (0, e1, e2, e3) applied to x^a y^b z^c.
double quadrature_of_monomial(int a, int b, int c) {
  double sum = 0;
  for (const auto& q : tet_quadrature_degree5()) {
    const double x = q.bary[1], y = q.bary[2], z = q.bary[3];
    sum += q.weight * std::pow(x, a) * std::pow(y, b) * std::pow(z, c);
  }
  return sum / 6.0;  // |T| = 1/6
}

}  // namespace

TEST_SUITE("property") {
  TEST_CASE("the degree-5 tet rule integrates every monomial of degree <= 5 exactly - not degree 6") {
    CHECK(tet_quadrature_degree5().size() == 15);
    for (int a = 0; a <= 5; ++a)
      for (int b = 0; a + b <= 5; ++b)
        for (int c = 0; a + b + c <= 5; ++c) {
          CAPTURE(a);
          CAPTURE(b);
          CAPTURE(c);
          // int x^a y^b z^c over the reference tet = a! b! c! / (a + b + c + 3)!
          const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          CHECK(quadrature_of_monomial(a, b, c) == doctest::Approx(exact).epsilon(1e-12));
        }
    CHECK(quadrature_of_monomial(6, 0, 0) != doctest::Approx(factorial(6) / factorial(9)).epsilon(1e-6));
  }

  TEST_CASE("the L2 interpolation error is zero for linear fields and falls by 4 when h halves") {
    const ScalarFunction linear = [](const Point& p) { return 1.0 + 2.0 * p.x() - 3.0 * p.y() + 0.5 * p.z(); };
    const ScalarFunction smooth = [](const Point& p) {
      return std::sin(3.0 * p.x()) * std::cos(2.0 * p.y()) + p.z() * p.z();
    };
    Mesh coarse = make_box({.nx = 4, .ny = 4, .nz = 4});
    Mesh fine = make_box({.nx = 8, .ny = 8, .nz = 8});
    CHECK(l2_interpolation_error(coarse, values_at_vertices(coarse, linear), linear) < 1e-13);
    const double e_coarse = l2_interpolation_error(coarse, values_at_vertices(coarse, smooth), smooth);
    const double e_fine = l2_interpolation_error(fine, values_at_vertices(fine, smooth), smooth);
    INFO("errors " << e_coarse << " " << e_fine);
    CHECK(e_coarse / e_fine == doctest::Approx(4.0).epsilon(0.1));
    CHECK(l2_difference(fine, values_at_vertices(fine, linear), values_at_vertices(fine, linear)) == 0.0);
  }

  TEST_CASE("point location finds the tet of every point - a field transfer is exact for linear fields") {
    const Mesh from = jittered_box(5, 0.3, 7);
    const Mesh to = jittered_box(7, 0.3, 11);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    TetId hint = kNoId;
    for (int i = 0; i < 500; ++i) {
      const Point p(u(rng), u(rng), u(rng));
      const Location loc = locate(from, p, hint);
      hint = loc.tet;
      REQUIRE(loc.inside);
      Point back = Point::Zero();
      for (int k = 0; k < 4; ++k) {
        CHECK(loc.bary[k] >= 0.0);
        back += loc.bary[k] * from.point(from.tet(loc.tet)[k]);
      }
      CHECK((back - p).norm() < 1e-12);
    }
    const ScalarFunction linear = [](const Point& p) { return 2.0 - p.x() + 4.0 * p.y() + 0.25 * p.z(); };
    std::size_t outside = 1;
    const auto moved = interpolate_vertex_field(from, values_at_vertices(from, linear), to, &outside);
    CHECK(outside == 0);
    for (VertexId v = 0; v < to.vertex_capacity(); ++v)
      if (to.vertex_alive(v)) CHECK(moved[v] == doctest::Approx(linear(to.point(v))).epsilon(1e-12));
    // A point outside the mesh: clamped into the closest tet, reported.
    const Location far = locate(from, Point(1.5, 0.5, 0.5));
    CHECK_FALSE(far.inside);
    CHECK(from.tet_alive(far.tet));
  }
}

TEST_SUITE("regression") {
  TEST_CASE("a quick adaptive loop on sinfun3: valid meshes, and the error falls when the complexity doubles") {
    Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    LoopOptions o;
    o.field = [](const Point& p) { return evaluate(AnalyticField::sinfun3, p); };
    o.iterations = 6;
    o.double_every = 3;
    o.complexity = 1000;
    o.concurrency = "serial";
    o.interpolate = true;
    o.on_iteration = [](const LoopRow&, const Mesh& m) { require_valid(m, 1.0); };
    const auto rows = adaptive_loop(mesh, o);
    REQUIRE(rows.size() == 6);
    double e1 = 0, e2 = 0;
    for (int i = 1; i < 3; ++i) e1 += rows[i].l2_error / 2;  // iterations 2-3 (1000)
    for (int i = 4; i < 6; ++i) e2 += rows[i].l2_error / 2;  // iterations 5-6 (2000)
    INFO("errors at 1000 and 2000: " << e1 << " " << e2 << ", vertices " << rows[2].vertices << " "
                                     << rows[5].vertices);
    CHECK(rows[5].complexity == 2000);
    CHECK(rows[5].vertices > rows[2].vertices);
    CHECK(e2 < 0.85 * e1);
    for (const auto& r : rows) {
      CHECK(r.transfer_error >= r.l2_error * 0.5);  // a transferred field is no better than the exact one
      CHECK(r.conformity > 0.8);
    }
    const std::string csv = loop_csv(rows);
    CHECK(csv.rfind("iteration,complexity,vertices,tets,seconds,l2_error", 0) == 0);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 7);
  }
}
