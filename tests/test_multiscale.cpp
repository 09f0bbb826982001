// Metric fields made from data: dual volumes and complexity, scaling to a
// target, gradation, Hessian recovery and the multiscale metric; analytic
// fields; and the errors a user gets for bad input.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/gradation.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/metrics/recovery.hpp>

#include <doctest/doctest.h>

#include <numeric>
#include <optional>

using namespace metrica;

namespace {

std::vector<Point> points_of(const Mesh& mesh) {
  std::vector<Point> p(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) p[v] = mesh.point(v);
  return p;
}

// u = 1/2 x^T A x + b.x + c with a fixed symmetric A.
const Sym6 kQuadratic = {2.0, 0.5, -1.0, 0.25, 0.75, 3.0};
double quadratic(const Point& p) {
  return 0.5 * p.dot(to_matrix(kQuadratic) * p) + 0.3 * p.x() - 0.2 * p.y() + 0.1 * p.z() + 1.0;
}

// Vertices whose whole star is interior (no boundary vertex among their
// neighbours): where L2-projection recovery is exact for quadratics.
std::vector<bool> deep_interior(const Mesh& mesh, const BoxSpec& b) {
  auto interior = [&](VertexId v) {
    const Point& p = mesh.point(v);
    for (int i = 0; i < 3; ++i)
      if (p[i] <= b.lo[i] + 1e-12 || p[i] >= b.hi[i] - 1e-12) return false;
    return true;
  };
  std::vector<bool> deep(mesh.vertex_capacity(), true);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (!interior(v)) deep[v] = false;
  for (const auto& [a, c] : unique_edges(mesh)) {
    if (!interior(a)) deep[c] = false;
    if (!interior(c)) deep[a] = false;
  }
  return deep;
}

// The complexity from each tensor's eigenvalues (not from its entries):
// the check of a field whose tensors are far from isotropic.
double eigen_complexity(const Mesh& mesh, const std::vector<Sym6>& m) {
  const auto dual = dual_volumes(mesh);
  double c = 0.0;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) c += std::sqrt(eigen_decomposition(m[v]).values.cwiseMax(0.0).prod()) * dual[v];
  return c;
}

Matrix3 random_rotation(std::mt19937_64& r) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double q3 = u(r), q2 = u(r), q1 = u(r), q0 = u(r);
  return Eigen::Quaterniond(Eigen::Vector4d(q0, q1, q2, q3).normalized()).toRotationMatrix();
}

// Every tensor finite and SPD, the complexity the target to 1e-6.
void check_front_metric(const Mesh& mesh, const std::vector<Sym6>& m, double target) {
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    REQUIRE(is_spd(m[v]));
  }
  CHECK(std::abs(eigen_complexity(mesh, m) / target - 1.0) < 1e-6);
  CHECK(std::abs(complexity(mesh, m) / target - 1.0) < 1e-6);
}

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("dual volumes sum to the domain volume and complexity of a constant metric is h^-3 V") {
    const Mesh mesh = make_box({.nx = 3, .ny = 4, .nz = 5, .lo = Point(0, 0, 0), .hi = Point(2, 1, 1)});
    const auto dual = dual_volumes(mesh);
    CHECK(std::accumulate(dual.begin(), dual.end(), 0.0) == doctest::Approx(2.0).epsilon(1e-13));
    const std::vector<Sym6> field(mesh.vertex_capacity(), isotropic_metric(0.1));
    CHECK(complexity(field, dual) == doctest::Approx(2000.0).epsilon(1e-12));
    auto scaled = field;
    scale_to_complexity(scaled, dual, 12345.0);
    CHECK(complexity(scaled, dual) == doctest::Approx(12345.0).epsilon(1e-12));
    CHECK_THROWS_AS(scale_to_complexity(scaled, dual, 0.0), InputError);
    CHECK_THROWS_AS(scale_to_complexity(scaled, dual, -5.0), InputError);
    CHECK_THROWS_AS(scale_to_complexity(scaled, dual, std::nan("")), InputError);
  }

  TEST_CASE("the complexity of linear on a fine cube is 4651.7 within 1 percent") {
    // h_z varies from 0.001 to 0.1 in z: a fine grid in z resolves it.
    const Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 800});
    const auto field = analytic_metric_field(AnalyticMetric::linear, points_of(mesh));
    const double c = complexity(mesh, field);
    MESSAGE("complexity of linear on a 2x2x800 box: " << c);
    CHECK(c == doctest::Approx(100.0 * std::log(100.0) / 0.099).epsilon(0.01));
  }

  TEST_CASE("analytic fields: names and values") {
    for (const auto& n : analytic_field_names()) CHECK(to_string(analytic_field_from_name(n)) == n);
    CHECK_THROWS_AS(analytic_field_from_name("sinfun"), InputError);
    CHECK(evaluate(AnalyticField::sinfun3, Point(0.4, 0.7, 0.9)) == 0.0);
    CHECK(evaluate(AnalyticField::tanh3, Point(0.5, 0.5, 0.0)) == 0.0);
    // In the strong shell sinfun3 is sin(50 s); outside it is damped.
    const Point in(0.5, 0.5, 0.5);  // s = 0.001
    CHECK(evaluate(AnalyticField::sinfun3, in) == doctest::Approx(std::sin(0.05)));
    const Point out(1.0, 1.0, 1.0);  // s = 0.216 > 2 pi / 50
    CHECK(evaluate(AnalyticField::sinfun3, out) == doctest::Approx(0.1 * std::sin(50 * 0.216)));
    CHECK(evaluate(AnalyticField::sinatan3, Point(0.2, 0.3, 0.4)) ==
          doctest::Approx(0.1 * std::sin(50 * 0.08) + std::atan(0.1 / (std::sin(1.5) - 0.16))));
  }
}

TEST_SUITE("property") {
  TEST_CASE("multiscale metrics of rotated rank-1 and rank-2 Hessians and of planar and cylindrical fronts") {
    // A Hessian of rank one or two along random axes (a planar or a
    // cylindrical front): its determinant from the entries cancels to zero
    // or below; the metric must still be finite and SPD and hit its target.
    const Mesh mesh = make_box({.nx = 6, .ny = 6, .nz = 6});
    auto r = test::rng(67);
    std::uniform_real_distribution<double> e(0.0, 1.0);
    MultiscaleOptions o;
    o.complexity = 2000.0;
    o.gradation = false;
    o.complexity_tolerance = 1e-9;
    o.max_relaxations = 60;
    for (int trial = 0; trial < 40; ++trial) {
      const int rank = 1 + trial % 2;
      CAPTURE(trial);
      std::vector<Sym6> hessian(mesh.vertex_capacity());
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
        const Matrix3 q = random_rotation(r);
        const Eigen::Vector3d l(std::pow(10.0, 6 * e(r) - 3), rank == 2 ? std::pow(10.0, 6 * e(r) - 3) : 0.0, 0.0);
        hessian[v] = to_sym6(q * l.asDiagonal() * q.transpose());
      }
      o.bounds = trial % 4 < 2 ? MetricBounds{} : MetricBounds{.hmin = 1e-3, .hmax = 0.5, .max_anisotropy = 100};
      const auto m = multiscale_metric_from_hessian(mesh, hessian, o);
      check_front_metric(mesh, m, o.complexity);
    }
    // The fields themselves: tanh(10 (n.x - c)) and tanh(10 (|x - a|_perp - r)).
    const auto pts = points_of(mesh);
    for (int trial = 0; trial < 6; ++trial) {
      const Eigen::Vector3d n = random_rotation(r).col(0);
      std::vector<double> u(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const Eigen::Vector3d d = pts[i] - Point(0.5, 0.5, 0.5);
        u[i] = trial % 2 == 0 ? std::tanh(10.0 * n.dot(d)) : std::tanh(10.0 * ((d - n.dot(d) * n).norm() - 0.3));
      }
      CAPTURE(trial);
      o.bounds = {};
      check_front_metric(mesh, multiscale_metric(mesh, u, o), o.complexity);
    }
  }

  TEST_CASE("recovered gradient of a linear field is exact and Hessian of a quadratic is exact inside") {
    const BoxSpec spec{.nx = 6, .ny = 5, .nz = 7, .lo = Point(-1, 0, 0.5), .hi = Point(1, 1, 2)};
    const Mesh mesh = make_box(spec);
    const auto pts = points_of(mesh);
    std::vector<double> linear(pts.size()), quad(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      linear[i] = 2.0 * pts[i].x() - 3.0 * pts[i].y() + 0.5 * pts[i].z();
      quad[i] = quadratic(pts[i]);
    }
    for (const auto& g : recover_gradient(mesh, linear)) CHECK((g - Eigen::Vector3d(2.0, -3.0, 0.5)).norm() < 1e-12);
    const auto h = recover_hessian(mesh, quad);
    const auto deep = deep_interior(mesh, spec);
    int checked = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      if (!deep[v]) continue;
      ++checked;
      for (int c = 0; c < 6; ++c) CHECK(h[v][c] == doctest::Approx(kQuadratic[c]).epsilon(1e-10).scale(1.0));
    }
    CHECK(checked == 3 * 2 * 4);
  }

  TEST_CASE("boundary extrapolation: interior Hessians kept, boundary ones from interior neighbours") {
    const BoxSpec spec{.nx = 6, .ny = 6, .nz = 6};
    const Mesh mesh = make_box(spec);
    const auto pts = points_of(mesh);
    std::vector<double> quad(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) quad[i] = quadratic(pts[i]);
    const auto raw = recover_hessian(mesh, quad);
    auto fixed = raw;
    CHECK(extrapolate_hessian_to_boundary(mesh, fixed) >= 1);
    double before = 0, after = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      const bool boundary = mesh.vertex_class(v) != VertexClass::interior;
      for (int c = 0; c < 6; ++c) {
        if (!boundary)
          CHECK(fixed[v][c] == raw[v][c]);
        else {
          before = std::max(before, std::abs(raw[v][c] - kQuadratic[c]));
          after = std::max(after, std::abs(fixed[v][c] - kQuadratic[c]));
        }
      }
    }
    // The one-sided projection is off by O(1) at the boundary; the interior
    // neighbours' mean is much closer (only the first layer is inexact).
    CHECK(after < 0.5 * before);

    // A field that is exact inside and garbage on the boundary comes back
    // exact everywhere, corners included (they wait for a filled neighbour).
    std::vector<Sym6> h(mesh.vertex_capacity(), kQuadratic);
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      if (mesh.vertex_class(v) != VertexClass::interior) h[v] = Sym6{9, 9, 9, 9, 9, 9};
    extrapolate_hessian_to_boundary(mesh, h);
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      for (int c = 0; c < 6; ++c) CHECK(h[v][c] == doctest::Approx(kQuadratic[c]).epsilon(1e-12).scale(1.0));

    std::vector<Sym6> wrong(3);
    CHECK_THROWS_AS(extrapolate_hessian_to_boundary(mesh, wrong), InputError);
  }

  TEST_CASE("multiscale metric hits the target complexity") {
    const Mesh mesh = make_box({.nx = 8, .ny = 8, .nz = 8});
    for (AnalyticField f : {AnalyticField::sinfun3, AnalyticField::tanh3, AnalyticField::sinatan3}) {
      const auto values = analytic_field_values(f, points_of(mesh));
      for (bool graded : {false, true}) {
        MultiscaleOptions o;
        o.complexity = 4000.0;
        o.gradation = graded;
        o.bounds = {.hmin = 1e-4, .hmax = 0.5};
        MultiscaleReport report;
        const auto m = multiscale_metric(mesh, values, o, &report);
        CAPTURE(to_string(f));
        CAPTURE(graded);
        CHECK(report.complexity == doctest::Approx(4000.0).epsilon(0.01));
        CHECK(complexity(mesh, m) == doctest::Approx(report.complexity).epsilon(1e-12));
        CHECK_NOTHROW(check_metric_field(m, "multiscale"));
      }
    }
  }

  TEST_CASE("multiscale metric of a quadratic is constant inside and scales with the complexity") {
    const BoxSpec spec{.nx = 6, .ny = 6, .nz = 6};
    const Mesh mesh = make_box(spec);
    const auto pts = points_of(mesh);
    std::vector<double> u(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) u[i] = quadratic(pts[i]);
    MultiscaleOptions o;
    o.gradation = false;
    o.complexity = 1000.0;
    const auto m1 = multiscale_metric(mesh, u, o);
    o.complexity = 8000.0;
    const auto m8 = multiscale_metric(mesh, u, o);
    const auto deep = deep_interior(mesh, spec);
    std::optional<Sym6> first;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      if (!deep[v]) continue;
      if (!first) first = m1[v];
      for (int c = 0; c < 6; ++c) {
        CHECK(m1[v][c] == doctest::Approx((*first)[c]).epsilon(1e-9).scale(1.0));
        // Complexity x8 -> sizes / 2 -> tensors x4.
        CHECK(m8[v][c] == doctest::Approx(4.0 * m1[v][c]).epsilon(1e-9).scale(1.0));
      }
    }
    // There it is a multiple of |H| (absolute eigenvalues of the Hessian).
    auto e = eigen_decomposition(kQuadratic);
    const Sym6 abs_h = to_sym6(e.vectors * e.values.cwiseAbs().asDiagonal() * e.vectors.transpose());
    const double s = (*first)[0] / abs_h[0];
    for (int c = 0; c < 6; ++c) CHECK((*first)[c] == doctest::Approx(s * abs_h[c]).epsilon(1e-9).scale(s));
  }

  TEST_CASE("several fields: each scaled on its own then intersected - a linear one left out - the target kept") {
    const BoxSpec spec{.nx = 6, .ny = 6, .nz = 6};
    const Mesh mesh = make_box(spec);
    const auto pts = points_of(mesh);
    std::vector<double> u(pts.size()), w(pts.size()), w_big(pts.size()), linear(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      u[i] = quadratic(pts[i]);
      w[i] = pts[i].x() * pts[i].x() - 3.0 * pts[i].y() * pts[i].z();
      w_big[i] = 1e4 * w[i];
      linear[i] = 2.0 * pts[i].x() - pts[i].z();
    }
    MultiscaleOptions o;
    o.complexity = 2000.0;
    o.gradation = false;
    MultiscaleReport report;
    const auto both = multiscale_metric(mesh, std::vector<std::vector<double>>{u, w}, o, &report);
    CHECK(report.complexity == doctest::Approx(2000.0).epsilon(0.01));
    CHECK(complexity(mesh, both) == doctest::Approx(report.complexity).epsilon(1e-12));
    CHECK_NOTHROW(check_metric_field(both, "intersected"));
    // A field's magnitude does not weigh: each is scaled to the complexity first.
    const auto scaled = multiscale_metric(mesh, std::vector<std::vector<double>>{u, w_big}, o);
    // The order does not matter either.
    const auto swapped = multiscale_metric(mesh, std::vector<std::vector<double>>{w, u}, o);
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      for (int c = 0; c < 6; ++c) {
        const double scale = std::abs(both[v][0]) + std::abs(both[v][2]) + std::abs(both[v][5]);
        CHECK(scaled[v][c] == doctest::Approx(both[v][c]).epsilon(1e-9).scale(scale));
        CHECK(swapped[v][c] == doctest::Approx(both[v][c]).epsilon(1e-9).scale(scale));
      }
    // The intersection asks for at least what each field asks (both scaled to
    // the same complexity, the intersection then scaled down to it): at the
    // deep vertices, along each field's own eigenvectors, the result is
    // above the field's metric times the common factor (C_both / C_sum)^(2/3).
    const auto alone_u = multiscale_metric(mesh, u, o);
    const auto deep = deep_interior(mesh, spec);
    int compared = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      if (!deep[v]) continue;
      ++compared;
      const Eigen::Matrix3d mb = to_matrix(both[v]), mu = to_matrix(alone_u[v]);
      const auto e = eigen_decomposition(alone_u[v]);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = e.vectors.col(k);
        CHECK(d.dot(mb * d) >= 0.2 * d.dot(mu * d));
      }
    }
    CHECK(compared > 0);
    // A linear field asks for nothing: the result is the other field's alone.
    const auto with_linear = multiscale_metric(mesh, std::vector<std::vector<double>>{u, linear}, o);
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      for (int c = 0; c < 6; ++c)
        CHECK(with_linear[v][c] == doctest::Approx(alone_u[v][c]).epsilon(1e-9).scale(std::abs(alone_u[v][0])));
    CHECK_THROWS_WITH_AS(multiscale_metric(mesh, std::vector<std::vector<double>>{linear, linear}, o),
                         doctest::Contains("linear"), InputError);
    CHECK_THROWS_AS(multiscale_metric(mesh, std::vector<std::vector<double>>{}, o), InputError);
  }

  TEST_CASE("fields chosen from a solution: K - K.x - all - the first scalar by default - errors named") {
    io::SolData sol;
    sol.count = 3;
    sol.types = {io::SolType::vector, io::SolType::scalar, io::SolType::sym_matrix};
    for (std::size_t v = 0; v < sol.count; ++v) {
      const double b = 100.0 * static_cast<double>(v);
      for (double x : {b + 1, b + 2, b + 3, b + 4, b + 5, b + 6, b + 7, b + 8, b + 9, b + 10}) sol.values.push_back(x);
    }
    auto names = [](const std::vector<SelectedField>& f) {
      std::string out;
      for (const auto& x : f) out += (out.empty() ? "" : " ") + x.name;
      return out;
    };
    const auto all = select_fields(sol, 3, "1,2", "s.sol");
    CHECK(names(all) == "1.x 1.y 1.z 2");
    REQUIRE(all.size() == 4);
    CHECK(all[1].values == std::vector<double>{2, 102, 202});
    CHECK(all[3].values == std::vector<double>{4, 104, 204});
    CHECK(names(select_fields(sol, 3, "all", "s.sol")) == "1.x 1.y 1.z 2");
    const auto y = select_fields(sol, 3, "1.y,1.3", "s.sol");
    CHECK(names(y) == "1.y 1.z");
    CHECK(y[1].values == std::vector<double>{3, 103, 203});
    const auto first = select_fields(sol, 3, "", "s.sol");
    REQUIRE(first.size() == 1);
    CHECK(first[0].values == std::vector<double>{4, 104, 204});
    CHECK_THROWS_WITH_AS(select_fields(sol, 3, "3", "s.sol"), doctest::Contains("symmetric"), InputError);
    CHECK_THROWS_WITH_AS(select_fields(sol, 3, "4", "s.sol"), doctest::Contains("fields 1 to 3"), InputError);
    CHECK_THROWS_AS(select_fields(sol, 3, "0", "s.sol"), InputError);
    CHECK_THROWS_WITH_AS(select_fields(sol, 3, "2.x", "s.sol"), doctest::Contains("names no component"), InputError);
    CHECK_THROWS_AS(select_fields(sol, 3, "1.w", "s.sol"), InputError);
    CHECK_THROWS_AS(select_fields(sol, 3, "1,", "s.sol"), InputError);
    CHECK_THROWS_AS(select_fields(sol, 3, "x", "s.sol"), InputError);
    CHECK_THROWS_AS(select_fields(sol, 3, "99999999999", "s.sol"), InputError);
    CHECK_THROWS_WITH_AS(select_fields(sol, 4, "1", "s.sol"), doctest::Contains("4 vertices"), InputError);
    auto bad = sol;
    bad.values[11] = std::nan("");  // vertex 2, field 1.y
    CHECK_THROWS_WITH_AS(select_fields(bad, 3, "1", "s.sol"), doctest::Contains("vertex 2"), InputError);
    CHECK_NOTHROW(select_fields(bad, 3, "2", "s.sol"));
    // A solution to transfer: scalars and vectors only.
    CHECK_THROWS_WITH_AS(solution_values_from_sol(sol, 3, "s.sol"), doctest::Contains("field 3"), InputError);
    sol.types.pop_back();
    sol.values.clear();
    for (int i = 0; i < 12; ++i) sol.values.push_back(i);
    CHECK(solution_values_from_sol(sol, 3, "s.sol").size() == 12);
  }

  TEST_CASE("gradation bounds the size growth along every edge") {
    const Mesh mesh = make_box({.nx = 10, .ny = 10, .nz = 10});
    // Isotropic sizes: tiny at one corner, large elsewhere.
    std::vector<Sym6> field(mesh.vertex_capacity(), isotropic_metric(0.5));
    field[0] = isotropic_metric(0.001);
    const auto original = field;
    const double beta = 1.5;
    const auto stats = limit_gradation(mesh, field, {.beta = beta, .space = GradationSpace::metric, .max_passes = 50});
    CHECK(stats.changed_last_pass == 0);
    for (const auto& [a, b] : unique_edges(mesh)) {
      const double len = (mesh.point(b) - mesh.point(a)).norm();
      const double ha = 1.0 / std::sqrt(field[a][0]), hb = 1.0 / std::sqrt(field[b][0]);
      // Metric-space growth of an isotropic size: h_b <= h_a + |e| ln(beta).
      CHECK(hb <= (ha + len * std::log(beta)) * (1 + 2e-3));
      CHECK(ha <= (hb + len * std::log(beta)) * (1 + 2e-3));
    }
    // Gradation only refines.
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) CHECK(field[v][0] >= original[v][0] * (1 - 1e-12));
    CHECK(field[1][0] > original[1][0]);
    // Mixed space grows more slowly in the physical part; it refines too.
    auto mixed = original;
    limit_gradation(mesh, mixed, {.beta = beta, .space = GradationSpace::mixed, .max_passes = 50});
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) CHECK(mixed[v][0] >= original[v][0] * (1 - 1e-12));
    CHECK_THROWS_AS(limit_gradation(mesh, mixed, {.beta = 0.5}), InputError);
  }
}

TEST_SUITE("regression") {
  TEST_CASE("the multiscale metric of the planar front tanh(10 (x + y + z - 1.5)) on the 9x9x9 cube") {
    // Its Hessian is of rank one along (1, 1, 1): the entries' determinant
    // cancelled below zero and the complexity came out NaN ("zero
    // complexity") before any bound could act.
    const Mesh mesh = make_box({.nx = 8, .ny = 8, .nz = 8});
    const auto pts = points_of(mesh);
    std::vector<double> u(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) u[i] = std::tanh(10.0 * (pts[i].sum() - 1.5));
    MultiscaleOptions o;
    o.complexity = 2000.0;
    MultiscaleReport report;
    const auto m = multiscale_metric(mesh, u, o, &report);
    CHECK(report.complexity == doctest::Approx(2000.0).epsilon(o.complexity_tolerance));
    CHECK_NOTHROW(check_metric_field(m, "multiscale"));
  }

  TEST_CASE("multiscale metric rejects bad input with clear errors") {
    const Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    const auto pts = points_of(mesh);
    std::vector<double> u(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) u[i] = quadratic(pts[i]);
    MultiscaleOptions o;
    o.complexity = 0.0;
    CHECK_THROWS_AS(multiscale_metric(mesh, u, o), InputError);
    o.complexity = -10.0;
    CHECK_THROWS_AS(multiscale_metric(mesh, u, o), InputError);
    o.complexity = 100.0;
    o.norm = 0.5;
    CHECK_THROWS_AS(multiscale_metric(mesh, u, o), InputError);
    o.norm = 2.0;
    auto bad = u;
    bad[5] = std::nan("");
    CHECK_THROWS_WITH_AS(multiscale_metric(mesh, bad, o), doctest::Contains("vertex 6"), InputError);
    bad = u;
    bad.pop_back();
    CHECK_THROWS_AS(multiscale_metric(mesh, bad, o), InputError);
    std::vector<double> flat(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) flat[i] = pts[i].x() + 2 * pts[i].y();
    CHECK_THROWS_WITH_AS(multiscale_metric(mesh, flat, o), doctest::Contains("linear"), InputError);
  }
}
