// Plain floating-point geometry of points: volumes and orientation.
//
// These are the non-robust evaluations used for measures (volume, reports)
// and for the validity check of the mesh core. Robust sign decisions
// (Filtered / Exact precision policies) live in predicates/.
#pragma once

#include <metrica/ids.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace metrica {

// Six times the signed volume of (a, b, c, d): det[b-a, c-a, d-a].
// Positive when d lies on the side of the normal (b-a)x(c-a).
inline double orient3d_fast(const Point& a, const Point& b, const Point& c, const Point& d) {
  return (b - a).cross(c - a).dot(d - a);
}

inline double tet_volume(const Point& a, const Point& b, const Point& c, const Point& d) {
  return orient3d_fast(a, b, c, d) / 6.0;
}

inline double triangle_area(const Point& a, const Point& b, const Point& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// The (unnormalised) normal (b-a)x(c-a) of triangle abc.
inline Eigen::Vector3d triangle_normal(const Point& a, const Point& b, const Point& c) { return (b - a).cross(c - a); }

// Is p in the plane of triangle xyz to round-off (its distance from the
// plane at most 1e-13 of the points' spread)? Surfaces kept without a
// model are remade only within their planes.
inline bool in_plane(const Point& x, const Point& y, const Point& z, const Point& p) {
  const Eigen::Vector3d n = (y - x).cross(z - x);
  const double size = std::max({(y - x).norm(), (z - x).norm(), (p - x).norm()});
  return std::abs(n.dot(p - x)) <= 1e-13 * n.norm() * size;
}

// 1 - |cos| of the angle between the lines of two normals: 0 when the
// faces are parallel, whichever way they are oriented; 1 for a flat face.
inline double normal_deviation(const Eigen::Vector3d& n1, const Eigen::Vector3d& n2) {
  const double d = n1.norm() * n2.norm();
  if (d <= 0.0) return 1.0;
  return 1.0 - std::abs(n1.dot(n2)) / d;
}

}  // namespace metrica
