// The Exact precision policy: every predicate in exact rational arithmetic
// (GMP rationals through CGAL), with no filter. The reference the other
// policies are tested against; slow by design.
#include <metrica/predicates/precision.hpp>

#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>

namespace metrica {

namespace {
using Kernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
using P3 = Kernel::Point_3;
P3 exact(const Point& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

int Exact::orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
  return static_cast<int>(CGAL::orientation(exact(a), exact(b), exact(c), exact(d)));
}

int Exact::insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  return static_cast<int>(CGAL::side_of_oriented_sphere(exact(a), exact(b), exact(c), exact(d), exact(e)));
}

int Exact::incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
  return static_cast<int>(CGAL::coplanar_side_of_bounded_circle(exact(a), exact(b), exact(c), exact(d)));
}

}  // namespace metrica
