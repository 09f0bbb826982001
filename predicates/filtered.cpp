// The Filtered precision policy: CGAL's filtered predicates (static
// filter, interval arithmetic, exact fallback) on double input.
#include <metrica/predicates/precision.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Simple_cartesian.h>

namespace metrica {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = Kernel::Point_3;
P3 cgal(const Point& p) { return {p.x(), p.y(), p.z()}; }

using IntervalKernel = CGAL::Simple_cartesian<CGAL::Interval_nt<false>>;
using I3 = IntervalKernel::Point_3;
I3 interval(const Point& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

int Filtered::orient3d_cgal(const Point& a, const Point& b, const Point& c, const Point& d) {
  return static_cast<int>(CGAL::orientation(cgal(a), cgal(b), cgal(c), cgal(d)));
}

int Filtered::insphere_cgal(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  return static_cast<int>(CGAL::side_of_oriented_sphere(cgal(a), cgal(b), cgal(c), cgal(d), cgal(e)));
}

int Filtered::incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
  return static_cast<int>(CGAL::coplanar_side_of_bounded_circle(cgal(a), cgal(b), cgal(c), cgal(d)));
}

bool orient3d_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d) {
  CGAL::Protect_FPU_rounding<true> protect;
  return CGAL::is_certain(CGAL::orientation(interval(a), interval(b), interval(c), interval(d)));
}

bool insphere_filter_decides(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  CGAL::Protect_FPU_rounding<true> protect;
  return CGAL::is_certain(
      CGAL::side_of_oriented_sphere(interval(a), interval(b), interval(c), interval(d), interval(e)));
}

}  // namespace metrica
