// Laws of symmetric tensors: log/exp inverse to each other, the factor L
// with L^T L = M, SPD detection; accurate at anisotropy ratios of 1e8.
#include "test_support.hpp"

#include <metrica/metrics/measures.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <Eigen/Geometry>
#include <doctest/doctest.h>

using namespace metrica;

namespace {

using test::random_metric;
using test::rel_diff;

}  // namespace

TEST_SUITE("property") {
  TEST_CASE("spd_exp inverts spd_log on random tensors up to anisotropy 1e8") {
    auto r = test::rng(10);
    for (double ratio : {1.0, 1e2, 1e4, 1e8}) {
      for (int i = 0; i < 200; ++i) {
        const auto m = random_metric(r, ratio);
        CAPTURE(ratio);
        CHECK(rel_diff(spd_exp(spd_log(m)), m) < 1e-13);
        // The smallest eigenvalue survives too, to the limit its storage
        // allows: entries rounded relative to the largest eigenvalue fix
        // the smallest only to (ratio x machine epsilon).
        const auto e0 = eigen_decomposition(m).values[0], e1 = eigen_decomposition(spd_exp(spd_log(m))).values[0];
        CHECK(std::abs(e1 - e0) / e0 < 50.0 * ratio * std::numeric_limits<double>::epsilon());
      }
    }
  }

  TEST_CASE("spd_exp_fast agrees with spd_exp along every eigenvector, up to anisotropy 1e8") {
    // The quadratic form v^T M v of the fast exponential, relative to the
    // exact one, along M's eigenvectors (the weakest direction is where
    // rounding relative to the largest eigenvalue shows).
    auto r = test::rng(12);
    for (double ratio : {1.0, 1e2, 1e4, 1e8}) {
      double worst = 0.0;
      for (int i = 0; i < 300; ++i) {
        const auto m = random_metric(r, ratio);
        const auto l = spd_log(m);
        const auto exact = spd_exp(l), fast = spd_exp_fast(l);
        const auto e = eigen_decomposition(exact);
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d v = e.vectors.col(k);
          worst = std::max(worst, std::abs(metric_norm2(fast, v) - metric_norm2(exact, v)) / metric_norm2(exact, v));
        }
      }
      CAPTURE(ratio);
      CHECK(worst < (ratio <= 1e4 ? 1e-9 : 1e-6));
    }
    // Exact cases: log 0 is the identity; a multiple of the identity.
    CHECK(spd_exp_fast(Sym6{}) == Sym6{1, 0, 1, 0, 0, 1});
    // A non-finite logarithm gives NaN (and returns: the halving loop
    // would never end on an infinite norm).
    CHECK(std::isnan(spd_exp_fast(Sym6{std::numeric_limits<double>::infinity(), 0, 0, 0, 0, 0})[0]));
    CHECK(std::isnan(spd_exp_fast(Sym6{std::nan(""), 0, 0, 0, 0, 0})[2]));
    const auto iso = spd_exp_fast(spd_log(isotropic_metric(0.01)));
    CHECK(iso[0] == doctest::Approx(1e4).epsilon(1e-12));
    CHECK(iso[1] == 0.0);
  }

  TEST_CASE("the adjugate is det(M) M^-1 and sym_times is M v") {
    auto r = test::rng(13);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
      const auto m = random_metric(r, 1e4);
      const Matrix3 a = to_matrix(adjugate(m));
      CHECK((a * to_matrix(m) - determinant(m) * Matrix3::Identity()).norm() / (a.norm() * to_matrix(m).norm()) <
            1e-13);
      const Eigen::Vector3d v = test::draw_point(u, r);
      CHECK((sym_times(m, v) - to_matrix(m) * v).norm() <= 1e-14 * to_matrix(m).norm() * v.norm());
    }
  }

  TEST_CASE("the metric factor L gives M as its Gram matrix and metric norms") {
    auto r = test::rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
      const auto m = random_metric(r, 1e6);
      const Matrix3 l = metric_factor(m);
      CHECK((l.transpose() * l - to_matrix(m)).norm() / to_matrix(m).norm() < 1e-13);
      const Eigen::Vector3d v = test::draw_point(u, r);
      CHECK((l * v).squaredNorm() == doctest::Approx(metric_norm2(m, v)).epsilon(1e-10));
      CHECK(metric_norm2(m, v) == doctest::Approx(v.dot(to_matrix(m) * v)).epsilon(1e-12));
    }
  }
}

TEST_SUITE("unit") {
  TEST_CASE("identity and isotropic tensors") {
    const auto id = isotropic_metric(1.0);
    for (double x : spd_log(id)) CHECK(x == doctest::Approx(0.0));
    const auto m = isotropic_metric(0.1);
    CHECK(m[0] == doctest::Approx(100.0));
    CHECK(spd_log(m)[0] == doctest::Approx(std::log(100.0)));
    CHECK(determinant(m) == doctest::Approx(1e6));
  }

  TEST_CASE("a planar front's metric: det and mean ratio from the eigenvalues when the entries cancel") {
    // Size 5e-5 across the plane x + y + z = const, 1 along it: every entry
    // is about 1.1e8 while det M is 3.3e8, which the entries' cofactors
    // cannot resolve (they may give a negative det, so a NaN mean ratio).
    const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
    Eigen::Matrix3d frame;
    frame.col(0) = n;
    frame.col(1) = Eigen::Vector3d(1, -1, 0).normalized();
    frame.col(2) = n.cross(frame.col(1));
    const Sym6 m = metric_from_sizes(frame, Eigen::Vector3d(5.4e-5, 1.0, 1.0));
    const double expected = 1.0 / (5.4e-5 * 5.4e-5);
    CHECK(spd_determinant(m) == doctest::Approx(expected).epsilon(1e-6));
    // A tet stretched along the plane, thin across it.
    const TetPoints p{Point(0.5, 0.5, 0.5), Point(0.5, 0.5, 0.5) + frame.col(1), Point(0.5, 0.5, 0.5) + frame.col(2),
                      Point(0.5, 0.5, 0.5) + 1e-4 * n + 0.3 * frame.col(1)};
    const double q = mean_ratio(p, m);
    CHECK(std::isfinite(q));
    CHECK(q > 0.0);
    CHECK(metric_volume(p, m) > 0.0);
    // A well-conditioned tensor keeps the entries' determinant, to the bit.
    const Sym6 round = isotropic_metric(0.1);
    CHECK(spd_determinant(round) == determinant(round));
  }

  TEST_CASE("metric_from_sizes puts size h along each direction") {
    const Matrix3 dirs = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const auto m = metric_from_sizes(dirs, Eigen::Vector3d(0.1, 0.01, 2.0));
    // A segment of length h along direction i has unit metric length.
    CHECK(std::sqrt(metric_norm2(m, 0.1 * dirs.col(0))) == doctest::Approx(1.0));
    CHECK(std::sqrt(metric_norm2(m, 0.01 * dirs.col(1))) == doctest::Approx(1.0));
    CHECK(std::sqrt(metric_norm2(m, 2.0 * dirs.col(2))) == doctest::Approx(1.0));
  }

  TEST_CASE("is_spd rejects indefinite - singular and non-finite tensors") {
    CHECK(is_spd(isotropic_metric(3.0)));
    CHECK_FALSE(is_spd({1, 0, -1, 0, 0, 1}));
    CHECK_FALSE(is_spd({1, 1, 1, 0, 0, 1}));  // singular
    CHECK_FALSE(is_spd({1, 0, 1, 0, 0, std::nan("")}));
    CHECK_FALSE(is_spd({1, 0, 1, 0, 0, INFINITY}));
  }
}
