// The Precision policy: how sign decisions are taken (docs/architecture.md).
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
#include <metrica/policy_list.hpp>

#include <algorithm>
#include <cmath>
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

// A semi-static filter run inline before CGAL: the determinant in double
// with the a-priori error bounds of Shewchuk ("Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", 1997,
// bounds o3derrboundA and isperrboundA): when |det| exceeds the bound
// times the permanent, its sign is exact. Returns 0 when undecided (then
// the caller asks CGAL). Shewchuk's orientation is the opposite of ours;
// the signs are turned on return.
namespace detail {
inline constexpr double kEps = 0x1p-53;
inline constexpr double kOrientBound = (7.0 + 56.0 * kEps) * kEps;
inline constexpr double kInsphereBound = (16.0 + 224.0 * kEps) * kEps;
// Below this permanent, underflow could void the bounds.
inline constexpr double kTinyPermanent = 1e-250;

inline int orient3d_filter(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double adx = a.x() - d.x(), bdx = b.x() - d.x(), cdx = c.x() - d.x();
  const double ady = a.y() - d.y(), bdy = b.y() - d.y(), cdy = c.y() - d.y();
  const double adz = a.z() - d.z(), bdz = b.z() - d.z(), cdz = c.z() - d.z();
  const double bc = bdy * cdz - bdz * cdy, ca = cdy * adz - cdz * ady, ab = ady * bdz - adz * bdy;
  const double det = adx * bc + bdx * ca + cdx * ab;
  const double permanent = (std::abs(bdy * cdz) + std::abs(bdz * cdy)) * std::abs(adx) +
                           (std::abs(cdy * adz) + std::abs(cdz * ady)) * std::abs(bdx) +
                           (std::abs(ady * bdz) + std::abs(adz * bdy)) * std::abs(cdx);
  const double bound = kOrientBound * permanent;
  if (permanent < kTinyPermanent) return 0;
  if (det > bound) return -1;
  if (-det > bound) return 1;
  return 0;
}

inline int insphere_filter(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  const double aex = a.x() - e.x(), bex = b.x() - e.x(), cex = c.x() - e.x(), dex = d.x() - e.x();
  const double aey = a.y() - e.y(), bey = b.y() - e.y(), cey = c.y() - e.y(), dey = d.y() - e.y();
  const double aez = a.z() - e.z(), bez = b.z() - e.z(), cez = c.z() - e.z(), dez = d.z() - e.z();
  const double aexbey = aex * bey, bexaey = bex * aey, bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey, dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey, bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey, da = dexaey - aexdey;
  const double ac = aexcey - cexaey, bd = bexdey - dexbey;
  const double abc = aez * bc - bez * ac + cez * ab, bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd, dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez, blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez, dlift = dex * dex + dey * dey + dez * dez;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  using std::abs;
  const double aez_ = abs(aez), bez_ = abs(bez), cez_ = abs(cez), dez_ = abs(dez);
  const double ab_ = abs(aexbey) + abs(bexaey), bc_ = abs(bexcey) + abs(cexbey), cd_ = abs(cexdey) + abs(dexcey);
  const double da_ = abs(dexaey) + abs(aexdey), ac_ = abs(aexcey) + abs(cexaey), bd_ = abs(bexdey) + abs(dexbey);
  const double permanent =
      (cd_ * bez_ + bd_ * cez_ + bc_ * dez_) * alift + (da_ * cez_ + ac_ * dez_ + cd_ * aez_) * blift +
      (ab_ * dez_ + bd_ * aez_ + da_ * bez_) * clift + (bc_ * aez_ + ac_ * bez_ + ab_ * cez_) * dlift;
  const double bound = kInsphereBound * permanent;
  if (permanent < kTinyPermanent) return 0;
  if (det > bound) return -1;
  if (-det > bound) return 1;
  return 0;
}
}  // namespace detail

struct Filtered {
  static constexpr std::string_view name = "filtered";
  static int orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
    const int s = detail::orient3d_filter(a, b, c, d);
    return s != 0 ? s : orient3d_cgal(a, b, c, d);
  }
  static int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
    const int s = detail::insphere_filter(a, b, c, d, e);
    return s != 0 ? s : insphere_cgal(a, b, c, d, e);
  }
  static int incircle(const Point& a, const Point& b, const Point& c, const Point& d);
  // CGAL's filtered kernel alone (static filter, intervals, exact).
  static int orient3d_cgal(const Point& a, const Point& b, const Point& c, const Point& d);
  static int insphere_cgal(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);
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

// The precisions offered by name (--precision), the default first.
using Precisions = PolicyList<Filtered, Exact, Fast>;

// Whether a tet an operation would make counts as positive: its double
// orientation above four times the rounding error bound of any vertex
// order (Shewchuk's for orient3d, 7.8e-16 times the permanent of the edge
// vectors, which is at most 6 L^3 whatever the order, L the largest
// coordinate difference along an edge). Above it the sign is certain and
// every order computes it positive, so every Precision agrees and no exact
// stage is needed; at or below it the tet is refused whatever its exact
// sign: validate() and the programs that read the output measure
// orientation in doubles, in whichever order the tet is stored.
inline bool positive_tet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
  const double l =
      std::max({u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff(), w.cwiseAbs().maxCoeff(),
                (c - b).cwiseAbs().maxCoeff(), (d - b).cwiseAbs().maxCoeff(), (d - c).cwiseAbs().maxCoeff()});
  return u.cross(v).dot(w) > 1.9e-14 * l * l * l;
}

// Whether interval arithmetic alone decides the sign (what the Filtered
// policy's filters do before its exact stage); for measuring how often
// the exact stage runs.
bool orient3d_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d);
bool insphere_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);

}  // namespace metrica
