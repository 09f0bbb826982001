// Laws of the geometric predicates under every Precision policy:
// antisymmetry of orient3d and insphere under odd permutations and
// invariance under even ones, on random and near-degenerate input
// (exactly coplanar / cospherical / cocircular integer points, and the same
// perturbed by 2^-45); Filtered agrees with Exact everywhere; how often
// Fast disagrees is reported, not asserted; positive_tet accepts only tets
// positive exactly and in doubles in any vertex order.
#include "test_support.hpp"

#include <metrica/predicates/precision.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

using namespace metrica;

namespace {

const double kTiny = std::ldexp(1.0, -45);

int parity(const std::array<int, 5>& p, int n) {
  int inversions = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) inversions += p[i] > p[j];
  return inversions % 2 == 0 ? 1 : -1;
}

template <class P>
int orient(const std::array<Point, 5>& x, const std::array<int, 5>& p) {
  return P::orient3d(x[p[0]], x[p[1]], x[p[2]], x[p[3]]);
}
template <class P>
int sphere(const std::array<Point, 5>& x, const std::array<int, 5>& p) {
  return P::insphere(x[p[0]], x[p[1]], x[p[2]], x[p[3]], x[p[4]]);
}

// Integer points on the sphere |x|^2 = 9 (exactly cospherical) and
// points in the plane z = 1 (exactly coplanar).
const std::array<Point, 12> kOnSphere = {Point(3, 0, 0),  Point(-3, 0, 0), Point(0, 3, 0),   Point(0, -3, 0),
                                         Point(0, 0, 3),  Point(0, 0, -3), Point(1, 2, 2),   Point(2, 1, -2),
                                         Point(-2, 2, 1), Point(2, -2, 1), Point(-1, -2, 2), Point(2, 2, -1)};

enum class Input { random, coplanar, cospherical };

std::array<Point, 5> draw(std::mt19937_64& r, Input kind, bool perturb) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(kOnSphere.size()) - 1), coin(-1, 1);
  std::array<Point, 5> x;
  switch (kind) {
    case Input::random:
      for (auto& p : x) p = test::draw_point(u, r);
      break;
    case Input::coplanar:
      for (auto& p : x) p = Point(std::round(8 * u(r)), std::round(8 * u(r)), 1.0);
      x[4] = test::draw_point(u, r);  // insphere's fifth point off the plane
      break;
    case Input::cospherical: {
      std::array<int, 12> idx;
      std::iota(idx.begin(), idx.end(), 0);
      std::shuffle(idx.begin(), idx.end(), r);
      for (int i = 0; i < 5; ++i) x[i] = kOnSphere[idx[i]];
      break;
    }
  }
  if (perturb)
    for (auto& p : x) p += kTiny * test::draw_point(coin, r);
  return x;
}

}  // namespace

TEST_SUITE("property") {
  TEST_CASE("a tet positive_tet accepts is positive exactly and in doubles in every even order of its vertices") {
    auto r = test::rng(51);
    int accepted = 0, near_flat = 0;
    for (int i = 0; i < 5000; ++i)
      for (Input kind : {Input::random, Input::coplanar})
        for (bool perturb : {false, true}) {
          const auto x = draw(r, kind, perturb);
          if (kind == Input::coplanar && perturb) ++near_flat;
          if (!positive_tet(x[0], x[1], x[2], x[3])) continue;
          ++accepted;
          CHECK(Exact::orient3d(x[0], x[1], x[2], x[3]) > 0);
          std::array<int, 4> p{0, 1, 2, 3};
          do {
            const int inversions =
                (p[0] > p[1]) + (p[0] > p[2]) + (p[0] > p[3]) + (p[1] > p[2]) + (p[1] > p[3]) + (p[2] > p[3]);
            if (inversions % 2 == 0) CHECK(orient3d_fast(x[p[0]], x[p[1]], x[p[2]], x[p[3]]) > 0.0);
          } while (std::next_permutation(p.begin(), p.end()));
        }
    CHECK(accepted > 2000);
    CHECK(near_flat == 5000);
  }

  TEST_CASE_TEMPLATE("orient3d and insphere change sign under odd permutations only", P, Fast, Filtered, Exact) {
    auto r = test::rng(100);
    for (Input kind : {Input::random, Input::coplanar, Input::cospherical}) {
      // Fast is only held to the law on random input: near degeneracy its
      // rounding is free to break it (counted in the next test).
      if (std::is_same_v<P, Fast> && kind != Input::random) continue;
      for (bool perturb : {false, true}) {
        for (int trial = 0; trial < 60; ++trial) {
          const auto x = draw(r, kind, perturb);
          std::array<int, 5> p{0, 1, 2, 3, 4};
          const int o0 = orient<P>(x, p), s0 = sphere<P>(x, p);
          do {
            CAPTURE(trial);
            if (p[4] == 4) CHECK(orient<P>(x, p) == parity(p, 4) * o0);
            CHECK(sphere<P>(x, p) == parity(p, 5) * s0);
          } while (std::next_permutation(p.begin(), p.end()));
        }
      }
    }
  }

  TEST_CASE("exactly degenerate integer input gives zero signs") {
    CHECK(Exact::orient3d(Point(0, 0, 1), Point(1, 0, 1), Point(0, 1, 1), Point(5, 7, 1)) == 0);
    CHECK(Filtered::orient3d(Point(0, 0, 1), Point(1, 0, 1), Point(0, 1, 1), Point(5, 7, 1)) == 0);
    CHECK(Exact::insphere(kOnSphere[0], kOnSphere[2], kOnSphere[4], kOnSphere[6], kOnSphere[7]) == 0);
    CHECK(Filtered::insphere(kOnSphere[0], kOnSphere[2], kOnSphere[4], kOnSphere[6], kOnSphere[7]) == 0);
    // orient3d > 0 means d on the side of (b-a)x(c-a), as the mesh core.
    const Point a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    for (int s : {Fast::orient3d(a, b, c, d), Filtered::orient3d(a, b, c, d), Exact::orient3d(a, b, c, d)})
      CHECK(s == 1);
    // insphere > 0 for a point inside a positive tet's circumsphere.
    const Point inside(0.25, 0.25, 0.25), outside(2, 2, 2);
    CHECK(Fast::insphere(a, b, c, d, inside) == 1);
    CHECK(Filtered::insphere(a, b, c, d, inside) == 1);
    CHECK(Exact::insphere(a, b, c, d, inside) == 1);
    CHECK(Fast::insphere(a, b, c, d, outside) == -1);
    CHECK(Filtered::insphere(a, b, c, d, outside) == -1);
    CHECK(Exact::insphere(a, b, c, d, outside) == -1);
  }

  TEST_CASE("Filtered agrees with Exact everywhere and Fast's disagreements are counted") {
    auto r = test::rng(101);
    const char* names[] = {"random", "coplanar", "cospherical"};
    for (Input kind : {Input::random, Input::coplanar, Input::cospherical}) {
      for (bool perturb : {false, true}) {
        int fast_orient = 0, fast_sphere = 0, calls = 0;
        for (int trial = 0; trial < 2000; ++trial) {
          const auto x = draw(r, kind, perturb);
          const int eo = Exact::orient3d(x[0], x[1], x[2], x[3]);
          const int es = Exact::insphere(x[0], x[1], x[2], x[3], x[4]);
          CHECK(Filtered::orient3d(x[0], x[1], x[2], x[3]) == eo);
          CHECK(Filtered::insphere(x[0], x[1], x[2], x[3], x[4]) == es);
          fast_orient += Fast::orient3d(x[0], x[1], x[2], x[3]) != eo;
          fast_sphere += Fast::insphere(x[0], x[1], x[2], x[3], x[4]) != es;
          ++calls;
        }
        if (kind == Input::random) {
          CHECK(fast_orient == 0);
          CHECK(fast_sphere == 0);
        }
        MESSAGE("Fast vs Exact on " << std::string(names[static_cast<int>(kind)])
                                    << std::string(perturb ? " + 2^-45" : "") << ": orient3d " << fast_orient << " / "
                                    << calls << " wrong, insphere " << fast_sphere << " / " << calls);
      }
    }
  }

  TEST_CASE_TEMPLATE("incircle of coplanar points is the bounded side and ignores the order of a b c", P, Fast,
                     Filtered, Exact) {
    auto r = test::rng(102);
    std::uniform_int_distribution<int> n(-6, 6);
    // Integer points of the tilted plane x + y + z = 1 (exactly coplanar)
    // and the cocircular points (3,4), (4,3), (5,0), (0,5), (-3,4)... of
    // radius 5 in the plane z = 2.
    const std::array<Point, 8> circle = {Point(3, 4, 2),  Point(4, 3, 2),  Point(5, 0, 2),  Point(0, 5, 2),
                                         Point(-3, 4, 2), Point(-5, 0, 2), Point(0, -5, 2), Point(4, -3, 2)};
    int fast_wrong = 0, calls = 0;
    for (int trial = 0; trial < 400; ++trial) {
      std::array<Point, 4> x;
      if (trial % 2 == 0) {
        for (auto& p : x) {
          const int a = n(r), b = n(r);
          p = Point(a, b, 1 - a - b);
        }
      } else {
        std::array<int, 8> idx;
        std::iota(idx.begin(), idx.end(), 0);
        std::shuffle(idx.begin(), idx.end(), r);
        for (int i = 0; i < 4; ++i) x[i] = circle[idx[i]];
        if (trial % 4 == 1) x[3] += kTiny * Point(1, -1, 0);  // in the plane, off the circle
      }
      // Small integers: the cross product is exact. Collinear: no circle.
      if ((x[1] - x[0]).cross(x[2] - x[0]).isZero(0.0)) continue;
      const int e = Exact::incircle(x[0], x[1], x[2], x[3]);
      std::array<int, 3> p{0, 1, 2};
      const int s = P::incircle(x[0], x[1], x[2], x[3]);
      if (std::is_same_v<P, Fast>) {
        fast_wrong += s != e;
        ++calls;
        continue;
      }
      CHECK(s == e);
      do CHECK(P::incircle(x[p[0]], x[p[1]], x[p[2]], x[3]) == s);
      while (std::next_permutation(p.begin(), p.end()));
      if (trial % 2 == 1 && trial % 4 != 1) CHECK(s == 0);  // exactly cocircular
    }
    // The bounded side is what a 2D in-circle says in the plane z = 2.
    CHECK(P::incircle(circle[0], circle[2], circle[3], Point(0, 0, 2)) == 1);
    CHECK(P::incircle(circle[0], circle[2], circle[3], Point(9, 9, 2)) == -1);
    if (calls) MESSAGE("Fast incircle vs Exact: " << fast_wrong << " / " << calls << " wrong");
  }
}
