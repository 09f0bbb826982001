// The Precision policy: how sign decisions are taken (DESIGN.md).
//
//   Fast      plain double evaluation; fastest, and wrong near degeneracy;
//   Filtered  CGAL's Exact_predicates_inexact_constructions_kernel: a
//             static floating-point filter, then interval arithmetic, then
//             exact arithmetic, so the sign is always the exact one;
//   Exact     exact rational arithmetic for every call (the reference).
//
// Signs (+1, 0, -1), for points taken exactly as given:
//   orient3d(a,b,c,d)    sign of det[b-a, c-a, d-a]: +1 when d lies on the
//                        side of the normal (b-a)x(c-a) (a positive tet);
//   insphere(a,b,c,d,e)  +1 when e is inside the sphere through a,b,c,d and
//                        orient3d(a,b,c,d) > 0; the sign flips with the
//                        orientation (odd permutations of a,b,c,d);
//   incircle(a,b,c,d)    for four coplanar points: +1 when d is inside the
//                        circle through a,b,c, 0 on it, -1 outside; it does
//                        not depend on the order of a,b,c. (For points off
//                        the plane it answers for the sphere through a,b,c
//                        centred in their plane.)
// CGAL is included only in this component's .cpp files.
#pragma once

#include <metrica/geometry.hpp>

#include <concepts>
#include <string_view>

namespace metrica {

template <class P>
concept Precision = requires(const Point& a) {
  { P::name } -> std::convertible_to<std::string_view>;
  { P::orient3d(a, a, a, a) } -> std::same_as<int>;
  { P::insphere(a, a, a, a, a) } -> std::same_as<int>;
  { P::incircle(a, a, a, a) } -> std::same_as<int>;
};

namespace detail {
inline int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

// det [[a-e, |a-e|^2], [b-e, ...], [c-e, ...], [d-e, ...]] expanded along
// the lifted column; its sign is opposite to "e inside" for a positive tet.
inline double insphere_det(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  const Eigen::Vector3d xa = a - e, xb = b - e, xc = c - e, xd = d - e;
  const double la = xa.squaredNorm(), lb = xb.squaredNorm(), lc = xc.squaredNorm(), ld = xd.squaredNorm();
  auto det3 = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
    return u.dot(v.cross(w));
  };
  return -la * det3(xb, xc, xd) + lb * det3(xa, xc, xd) - lc * det3(xa, xb, xd) + ld * det3(xa, xb, xc);
}
}  // namespace detail

struct Fast {
  static constexpr std::string_view name = "fast";
  static int orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
    return detail::sign_of(orient3d_fast(a, b, c, d));
  }
  static int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
    return -detail::sign_of(detail::insphere_det(a, b, c, d, e));
  }
  static int incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
    // Lift: the sphere through a, b, c and a + n (n normal to abc) meets
    // the plane of abc in the circle through a, b, c; (a,b,c,a+n) is a
    // positive tet, so the oriented insphere is the bounded side.
    const Point top = a + (b - a).cross(c - a);
    return insphere(a, b, c, top, d);
  }
};

struct Filtered {
  static constexpr std::string_view name = "filtered";
  static int orient3d(const Point& a, const Point& b, const Point& c, const Point& d);
  static int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);
  static int incircle(const Point& a, const Point& b, const Point& c, const Point& d);
};

struct Exact {
  static constexpr std::string_view name = "exact";
  static int orient3d(const Point& a, const Point& b, const Point& c, const Point& d);
  static int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);
  static int incircle(const Point& a, const Point& b, const Point& c, const Point& d);
};

static_assert(Precision<Fast>);
static_assert(Precision<Filtered>);
static_assert(Precision<Exact>);

// Whether interval arithmetic alone decides the sign (what the Filtered
// policy's filters do before its exact stage); for measuring how often
// the exact stage runs.
bool orient3d_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d);
bool insphere_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);

}  // namespace metrica
