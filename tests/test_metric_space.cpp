// Laws of the metric spaces and of the metric criteria built on them:
// lengths scale with the metric, mean ratio is 1 for the regular tet in
// its own metric and invariant under the metric's affine map, the
// log-Euclidean mean is symmetric and reproduces equal tensors,
// intersection is contained in both tensors, the metric Delaunay criterion
// is the Euclidean insphere for identity metrics.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/intersection.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/predicates/edge_weight.hpp>
#include <metrica/predicates/metric_delaunay.hpp>
#include <metrica/predicates/quality_criterion.hpp>

#include <Eigen/LU>
#include <doctest/doctest.h>

#include <iomanip>
#include <limits>

using namespace metrica;
using test::random_metric;
using test::rel_diff;

namespace {

// The regular tet, positively oriented.
const TetPoints kRegular = {Point(1, 1, 1), Point(1, -1, -1), Point(-1, -1, 1), Point(-1, 1, -1)};

// Lowest eigenvalue of x - y relative to |x|: >= -tol when x >= y.
double min_eig_of_difference(const Sym6& x, const Sym6& y) {
  Sym6 d;
  for (int c = 0; c < 6; ++c) d[c] = x[c] - y[c];
  return eigen_decomposition(d).values[0] / to_matrix(x).norm();
}

TetPoints random_tet(std::mt19937_64& r) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetPoints k;
  for (auto& p : k) p = test::draw_point(u, r);
  if (orient3d_fast(k[0], k[1], k[2], k[3]) < 0) std::swap(k[2], k[3]);
  return k;
}

TetPoints mapped(const Matrix3& a, const TetPoints& k) {
  TetPoints m;
  for (int i = 0; i < 4; ++i) m[i] = a * k[i];
  return m;
}

Mesh box_with_metric(std::mt19937_64& r, double ratio) {
  Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
  std::vector<Sym6> field(mesh.vertex_capacity());
  for (auto& m : field) m = random_metric(r, ratio);
  assign_metric(mesh, field);
  return mesh;
}

}  // namespace

TEST_SUITE("property") {
  TEST_CASE("mean ratio is 1 for the regular tet and invariant under the metric's affine map") {
    CHECK(mean_ratio(kRegular, isotropic_metric(1.0)) == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(mean_ratio(kRegular, isotropic_metric(0.01)) == doctest::Approx(1.0).epsilon(1e-14));
    auto r = test::rng(200);
    for (int i = 0; i < 200; ++i) {
      const Sym6 m = random_metric(r, 1e4);
      const Matrix3 l = metric_factor(m);
      // The regular tet of the metric's space, pulled back by L^-1.
      const TetPoints k = mapped(l.inverse(), kRegular);
      const double sign = l.determinant() > 0 ? 1.0 : -1.0;
      CHECK(sign * mean_ratio(k, m) == doctest::Approx(1.0).epsilon(1e-9));
      // Any tet: its quality in M is its Euclidean quality once mapped.
      const TetPoints t = random_tet(r);
      CHECK(std::abs(mean_ratio(t, m)) ==
            doctest::Approx(std::abs(mean_ratio(mapped(l, t), isotropic_metric(1.0)))).epsilon(1e-9));
      CHECK(mean_ratio(t, m) <= 1.0 + 1e-12);
    }
    // A flat tet has quality 0, an inverted one negative quality.
    CHECK(mean_ratio({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 1, 0)}, isotropic_metric(1)) == 0.0);
    CHECK(mean_ratio({kRegular[0], kRegular[1], kRegular[3], kRegular[2]}, isotropic_metric(1)) < 0.0);
  }

  TEST_CASE("the UGAWG edge length is the logarithmic mean of the end lengths, symmetric, l at equal ends") {
    auto r = test::rng(204);
    std::uniform_real_distribution<double> log_l(-8.0, 8.0), log_ratio(-0.6, 0.6);
    for (int i = 0; i < 20000; ++i) {
      // Ratios from 1 (the series) to e^0.6 (past its 1.29 bound: the log).
      const double la = std::exp(log_l(r)), lb = la * std::exp(i % 2 == 0 ? log_ratio(r) : 1e-3 * log_ratio(r));
      // la - lb is exact (Sterbenz); log1p keeps the ratio's digits.
      const long double exact = static_cast<long double>(la - lb) / std::log1p(static_cast<long double>(la - lb) / lb);
      INFO("la " << std::setprecision(17) << la << " lb " << lb);
      CHECK(ugawg_length(la, lb) == doctest::Approx(static_cast<double>(exact)).epsilon(1e-14));
      CHECK(ugawg_length(la, lb) == ugawg_length(lb, la));
      CHECK(ugawg_length(la, la) == doctest::Approx(la).epsilon(1e-15));
      CHECK(ugawg_length(la, lb) >= std::sqrt(la * lb) * (1 - 1e-15));  // geometric <= log <= arithmetic mean
      CHECK(ugawg_length(la, lb) <= 0.5 * (la + lb) * (1 + 1e-15));
    }
    CHECK(ugawg_length(0.0, 0.0) == 0.0);
    CHECK(std::isnan(ugawg_length(std::nan(""), 1.0)));
  }

  TEST_CASE("ugawg_length_in decides as the length does - inside, below, above and across the band") {
    auto r = test::rng(205);
    std::uniform_real_distribution<double> log_scale(-1.5, 1.5), u(-1.0, 1.0);
    const UnitBand bands[] = {kUnitBand, {0.0, 1.5}, {0.8, std::numeric_limits<double>::infinity()}};
    int inside = 0, outside = 0;
    for (int i = 0; i < 20000; ++i) {
      const Sym6 ma = random_metric(r, 1e3), mb = random_metric(r, 1e3);
      // Scaled so that the end lengths fall around the band's ends.
      const Eigen::Vector3d d = test::draw_point(u, r);
      const Eigen::Vector3d v = std::exp(log_scale(r)) * d / std::sqrt(metric_norm2(ma, d));
      for (const UnitBand& band : bands) {
        const bool expected = band.contains(ugawg_length(v, ma, mb));
        CHECK(ugawg_length_in(band, v, ma, mb) == expected);
        (expected ? inside : outside) += 1;
      }
    }
    CHECK(inside > 1000);
    CHECK(outside > 1000);
  }

  TEST_CASE_TEMPLATE("edge_length_in agrees with edge_length in every space", S, Isotropic, Anisotropic, LogEuclidean) {
    auto r = test::rng(206);
    Mesh mesh = box_with_metric(r, 1e2);
    int inside = 0;
    for (VertexId a = 0; a < mesh.vertex_capacity(); ++a)
      for (VertexId b = a + 1; b < mesh.vertex_capacity(); b += 7) {
        const double l = S::edge_length(mesh, a, b);
        const UnitBand band{0.5 * l, 2.0 * l};
        CHECK(S::edge_length_in(mesh, a, b, band));
        CHECK_FALSE(S::edge_length_in(mesh, a, b, {1.01 * l, 3.0 * l}));
        CHECK_FALSE(S::edge_length_in(mesh, a, b, {0.3 * l, 0.99 * l}));
        inside += S::edge_length_in(mesh, a, b, kUnitBand) == kUnitBand.contains(l);
      }
    CHECK(inside > 0);
  }

  TEST_CASE("mean_ratio_cubed from its parts is the cube of the mean ratio - sign kept") {
    auto r = test::rng(201);
    for (int i = 0; i < 200; ++i) {
      const Sym6 m = random_metric(r, 1e4);
      const TetPoints t = random_tet(r);
      double sum = 0.0;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) sum += metric_norm2(m, t[b] - t[a]);
      const double q3 = mean_ratio_cubed(orient3d_fast(t[0], t[1], t[2], t[3]), determinant(m), sum);
      CHECK(std::cbrt(q3) == doctest::Approx(mean_ratio(t, m)).epsilon(1e-12));
    }
    CHECK(mean_ratio_cubed(1.0, 1.0, 0.0) == 0.0);
  }

  TEST_CASE_TEMPLATE("space lengths scale by sqrt 2 when the metric doubles", S, Isotropic, Anisotropic, LogEuclidean) {
    auto r = test::rng(201);
    Mesh mesh = box_with_metric(r, 1e3);
    std::vector<double> before;
    for (VertexId a = 0; a + 1 < mesh.vertex_capacity(); ++a) before.push_back(S::edge_length(mesh, a, a + 1));
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      Sym6 m = mesh.metric(v);
      for (double& x : m) x *= 2.0;
      mesh.set_metric(v, m, spd_log(m));
    }
    for (VertexId a = 0; a + 1 < mesh.vertex_capacity(); ++a)
      CHECK(S::edge_length(mesh, a, a + 1) == doctest::Approx(std::sqrt(2.0) * before[a]).epsilon(1e-12));
  }

  TEST_CASE_TEMPLATE("space interpolation reproduces vertex metrics and tet qualities lie in 0 to 1", S, Isotropic,
                     Anisotropic, LogEuclidean) {
    auto r = test::rng(202);
    Mesh mesh = box_with_metric(r, 1e2);
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      const auto& k = mesh.tet(t);
      const std::array<double, 4> at_first{1, 0, 0, 0};
      const Sym6 m = S::metric_at(mesh, std::span<const VertexId>(k), at_first);
      const Sym6 expect = std::is_same_v<S, Isotropic> ? S::vertex_metric(mesh, k[0]) : mesh.metric(k[0]);
      // LogEuclidean measures through spd_exp_fast (relative error ~1e-11);
      // the other spaces reproduce the tensor to rounding.
      CHECK(rel_diff(m, expect) < (std::is_same_v<S, LogEuclidean> ? 1e-10 : 1e-12));
      const auto vm = S::interpolate(mesh, std::span<const VertexId>(k), at_first);
      CHECK(rel_diff(spd_exp(vm.log_m), vm.m) < 1e-12);
      const double q = S::mean_ratio(mesh, k);
      CHECK(q > 0.0);
      CHECK(q <= 1.0 + 1e-12);
      CHECK(std::cbrt(S::mean_ratio_cubed(mesh, k)) == doctest::Approx(q).epsilon(1e-12));
      TetVertices inverted = k;
      std::swap(inverted[0], inverted[1]);
      CHECK(std::cbrt(S::mean_ratio_cubed(mesh, inverted)) == doctest::Approx(-q).epsilon(1e-12));
      CHECK(S::metric_volume(mesh, k) > 0.0);
      CHECK(is_spd(S::tet_metric(mesh, k)));
    }
  }

  TEST_CASE_TEMPLATE(
      "a tet's metric with one vertex's metric replaced: the same with its own, the new one's "
      "share with another",
      S, Isotropic, Anisotropic, LogEuclidean) {
    auto r = test::rng(207);
    Mesh mesh = box_with_metric(r, 1e2);
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      const auto& k = mesh.tet(t);
      for (VertexId v : k) {
        const VertexMetric own{mesh.metric(v), mesh.log_metric(v)};
        CHECK(rel_diff(S::tet_metric_with(mesh, k, v, own), S::tet_metric(mesh, k)) < 1e-12);
      }
      // Another tet's metric at k[0]: as if that vertex stored it.
      Mesh moved = mesh;
      const VertexId u = mesh.tet(t == 0 ? 1 : 0)[2];
      const VertexMetric other{mesh.metric(u), mesh.log_metric(u)};
      moved.set_metric(k[0], other.m, other.log_m);
      CHECK(rel_diff(S::tet_metric_with(mesh, k, k[0], other), S::tet_metric(moved, k)) < 1e-12);
    }
  }

  TEST_CASE("log-Euclidean mean: equal tensors give that tensor and the mean is symmetric and SPD") {
    auto r = test::rng(203);
    for (int i = 0; i < 200; ++i) {
      const Sym6 m = random_metric(r, 1e6);
      const std::array<Sym6, 4> same{m, m, m, m};
      const std::array<double, 4> w{0.1, 0.2, 0.3, 0.4};
      CHECK(rel_diff(log_euclidean_mean(same, w), m) < 1e-12);
      const std::array<Sym6, 3> abc{random_metric(r, 1e3), random_metric(r, 1e3), random_metric(r, 1e3)};
      const std::array<Sym6, 3> cab{abc[2], abc[0], abc[1]};
      const std::array<double, 3> w3{0.5, 0.3, 0.2}, w3p{0.2, 0.5, 0.3};
      const Sym6 mean = log_euclidean_mean(abc, w3);
      CHECK(rel_diff(log_euclidean_mean(cab, w3p), mean) < 1e-12);
      CHECK(is_spd(mean));
      // The determinant of the log-Euclidean mean is the geometric mean.
      const double det =
          std::pow(determinant(abc[0]), 0.5) * std::pow(determinant(abc[1]), 0.3) * std::pow(determinant(abc[2]), 0.2);
      CHECK(determinant(mean) == doctest::Approx(det).epsilon(1e-8));
    }
  }

  TEST_CASE("intersection is contained in both tensors and intersect(m m) is m") {
    auto r = test::rng(204);
    for (int i = 0; i < 300; ++i) {
      const Sym6 a = random_metric(r, 1e4), b = random_metric(r, 1e4);
      CHECK(rel_diff(intersect(a, a), a) < 1e-10);
      const Sym6 x = intersect(a, b);
      CHECK(is_spd(x));
      CHECK(min_eig_of_difference(x, a) > -1e-10);
      CHECK(min_eig_of_difference(x, b) > -1e-10);
      CHECK(rel_diff(intersect(b, a), x) < 1e-8);
      // Nested tensors: the larger one wins.
      Sym6 big = a;
      for (double& c : big) c *= 4.0;
      CHECK(rel_diff(intersect(a, big), big) < 1e-10);
    }
  }

  TEST_CASE("metric bounds clamp sizes and anisotropy") {
    auto r = test::rng(205);
    const MetricBounds b{.hmin = 1e-3, .hmax = 0.5, .max_anisotropy = 100.0};
    for (int i = 0; i < 200; ++i) {
      const auto e = eigen_decomposition(clamp_metric(random_metric(r, 1e8), b)).values;
      // Recomposing the tensor rounds eigenvalues relative to the largest.
      CHECK(e[0] >= 1.0 / (0.5 * 0.5) - 1e-14 * e[2]);
      CHECK(e[2] <= 1.0 / (1e-3 * 1e-3) * (1 + 1e-12));
      CHECK(e[2] / e[0] <= 100.0 * 100.0 * (1 + 1e-9));
    }
    CHECK_THROWS_AS(check_bounds({.hmin = 1.0, .hmax = 0.5}), InputError);
    CHECK_THROWS_AS(check_bounds({.max_anisotropy = 0.5}), InputError);
    CHECK_THROWS_AS(check_bounds({.hmax = 0.0}), InputError);
  }

  TEST_CASE_TEMPLATE("metric Delaunay criterion is the Euclidean insphere for identity metrics", P, Fast, Filtered,
                     Exact) {
    auto r = test::rng(206);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Sym6 id = isotropic_metric(1.0);
    const std::array<Sym6, 4> ids{id, id, id, id};
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const TetPoints k = random_tet(r);
      // Half the trials: a point on the circumsphere up to 2^-45.
      Point p = test::draw_point(u, r);
      if (i % 2) {
        const Matrix3 rows =
            (Matrix3() << 2 * (k[1] - k[0]).transpose(), 2 * (k[2] - k[0]).transpose(), 2 * (k[3] - k[0]).transpose())
                .finished();
        const Eigen::Vector3d rhs((k[1] - k[0]).squaredNorm(), (k[2] - k[0]).squaredNorm(),
                                  (k[3] - k[0]).squaredNorm());
        const Point o = k[0] + rows.inverse() * rhs;
        p = o + (k[0] - o).norm() * test::draw_point(u, r).normalized();
      }
      const bool in = P::insphere(k[0], k[1], k[2], k[3], p) > 0;
      CHECK(metric_delaunay_violated<P>(k, p, ids, id) == in);
      inside += in;
      if (i % 2 == 0 && in != (delaunay_measure(k, p, Matrix3::Identity()) < 1.0)) FAIL("measure disagrees");
    }
    CHECK(inside > 100);
  }

  TEST_CASE("metric criteria are invariant under the metric's affine map") {
    auto r = test::rng(207);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 300; ++i) {
      const Sym6 m = random_metric(r, 1e3);
      const Matrix3 l = metric_factor(m);
      const TetPoints k = random_tet(r);
      const Point p = test::draw_point(u, r);
      const std::array<Sym6, 4> mk{m, m, m, m};
      const TetPoints mk_points = mapped(l, k);
      const Sym6 id = isotropic_metric(1.0);
      const Point lp = l * p;
      // Skip points within round-off of the sphere.
      if (std::abs(delaunay_measure(k, p, l) - 1.0) < 1e-9) continue;
      CHECK(metric_delaunay_violated<Filtered>(k, p, mk, m) ==
            (Filtered::orient3d(mk_points[0], mk_points[1], mk_points[2], mk_points[3]) *
                 Filtered::insphere(mk_points[0], mk_points[1], mk_points[2], mk_points[3], lp) >
             0));
      const auto w = edge_weights(k, m);
      auto wl = edge_weights(
          l.determinant() > 0 ? mk_points : TetPoints{mk_points[0], mk_points[1], mk_points[3], mk_points[2]}, id);
      if (l.determinant() < 0) {
        // The swap of vertices 2 and 3 permutes edges: (0,2)<->(0,3), (1,2)<->(1,3).
        std::swap(wl[1], wl[2]);
        std::swap(wl[3], wl[4]);
      }
      for (int e = 0; e < 6; ++e) CHECK(w[e] == doctest::Approx(wl[e]).epsilon(1e-8).scale(1.0));
    }
  }

  TEST_CASE("edge weights: equal and positive on the regular tet and negative at an obtuse dihedral") {
    const auto w = edge_weights(kRegular, isotropic_metric(1.0));
    for (double x : w) CHECK(x == doctest::Approx(w[0]).epsilon(1e-12));
    CHECK(w[0] > 0.0);
    // A sliver: four points near a square, dihedral angles near 0 and pi.
    const TetPoints sliver = {Point(0, 0, 0), Point(1, 1, 0), Point(1, 0, 0.05), Point(0, 1, 0.05)};
    const TetPoints k = orient3d_fast(sliver[0], sliver[1], sliver[2], sliver[3]) > 0
                            ? sliver
                            : TetPoints{sliver[0], sliver[1], sliver[3], sliver[2]};
    CHECK(min_edge_weight(k, isotropic_metric(1.0)) < 0.0);
    CHECK(improves_min_quality(0.2, 0.3));
    CHECK_FALSE(improves_min_quality(0.3, 0.3));
  }
}

TEST_SUITE("unit") {
  TEST_CASE("quality report of one Kuhn cube in the identity metric") {
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    assign_metric(mesh, std::vector<Sym6>(mesh.vertex_capacity(), isotropic_metric(1.0)));
    for (std::string_view s : {"isotropic", "anisotropic", "log-euclidean"}) {
      const auto r = quality_report(mesh, s);
      CHECK(r.vertices == 8);
      CHECK(r.tets == 6);
      CHECK(r.edges == 19);  // 12 sides, 6 face diagonals, 1 main diagonal
      CHECK(r.length.min == doctest::Approx(1.0));
      CHECK(r.length.max == doctest::Approx(std::sqrt(3.0)));
      CHECK(r.unit_length_share == doctest::Approx(18.0 / 19.0));
      CHECK(r.complexity == doctest::Approx(1.0));
      CHECK(r.volume == doctest::Approx(1.0));
      CHECK(r.quality.min == doctest::Approx(r.quality.max));  // 6 congruent tets
      CHECK(r.quality_below_03 == 0.0);
      std::size_t in_bins = 0;
      for (auto c : r.quality_histogram.counts) in_bins += c;
      CHECK(in_bins == 6);
    }
    CHECK_THROWS_AS(quality_report(mesh, "riemann"), InputError);
    Mesh bare = make_box({.nx = 1, .ny = 1, .nz = 1});
    CHECK_THROWS_AS(quality_report(bare), InputError);
  }

  TEST_CASE("quality report: the same to the bit on any runner, its parts in any order") {
    // Several blocks of edges (4096 lower ends each) and of tets (65536),
    // an anisotropic metric that varies, and holes left by deleted tets.
    Mesh mesh = make_box({.nx = 26, .ny = 26, .nz = 26});
    std::vector<Sym6> field(mesh.vertex_capacity());
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      const Point& p = mesh.point(v);
      field[v] = {1.0 + 30.0 * p.x() * p.x(), 0.3 * p.y(), 2.0 + p.z(), 0.1, 0.0, 5.0 + 10.0 * p.x() * p.y()};
    }
    assign_metric(mesh, field);
    for (TetId t = 0; t < mesh.tet_capacity(); t += 997) mesh.remove_tet(t);
    REQUIRE(mesh.vertex_capacity() > 3 * kEdgeBlockVertices);
    REQUIRE(mesh.tet_capacity() > 1u << 16);
    for (std::string_view s : {"isotropic", "anisotropic", "log-euclidean"}) {
      CAPTURE(s);
      const std::string one = report_csv(quality_report(mesh, s));
      for (std::size_t parts : {2u, 3u, 7u, 1000u}) {
        CAPTURE(parts);
        CHECK(report_csv(quality_report(mesh, s, {.run = test::reversed_parts(parts)})) == one);
      }
    }
  }

  TEST_CASE("quality report: a non-finite measure is an error - never a histogram bin out of range") {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      CAPTURE(bad);
      Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
      std::vector<Sym6> field(mesh.vertex_capacity(), isotropic_metric(1.0));
      field[0] = {bad, 0, 1, 0, 0, 1};
      assign_metric(mesh, field);
      for (std::string_view s : {"isotropic", "anisotropic", "log-euclidean"})
        CHECK_THROWS_AS(quality_report(mesh, s), InputError);
    }
  }
}
