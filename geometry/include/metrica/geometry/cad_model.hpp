// A CAD model read through gmsh's API and its OpenCASCADE kernel: the
// entities (model vertices, curves, surfaces), their adjacency, and the
// evaluations the adaptation needs (a point from parameters, a surface's
// normal, a boundary entity's parameters on a surface; a point's
// parameters by projection, for the first association only).
//
// gmsh holds one model per process: one CadModel may be open at a time.
// Every call into gmsh takes the model's lock (gmsh does not document its
// thread safety); the parameters of curves' ends and the periods are read
// once at opening so that the frequent questions need no call.
#pragma once

#include <metrica/ids.hpp>

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace metrica {

class CadModel {
 public:
  // Opens any file gmsh reads (.step .stp .iges .igs .brep .geo); throws
  // InputError when gmsh cannot, or when the model has no surface.
  explicit CadModel(const std::string& path);
  ~CadModel();
  CadModel(const CadModel&) = delete;
  CadModel& operator=(const CadModel&) = delete;

  const std::string& source() const { return source_; }
  // The diagonal of the model's bounding box (scale of the tolerances).
  double size() const { return size_; }
  const std::vector<int>& entities(int dim) const { return entities_[static_cast<std::size_t>(dim)]; }
  bool has(int dim, int tag) const;

  // Adjacency: the curves bounding a surface, the end vertices of a curve
  // (one for a closed curve, none for a periodic one without), and the
  // curves through a model vertex, the surfaces along a curve.
  const std::vector<int>& curves_of_surface(int s) const;
  const std::vector<int>& vertices_of_curve(int c) const;
  const std::vector<int>& curves_of_vertex(int v) const;
  const std::vector<int>& surfaces_of_curve(int c) const;

  // Parameter range and period (0: not periodic) of a curve (u only) or a
  // surface; a surface is periodic in u when its two u-borders coincide.
  struct Range {
    std::array<double, 2> lo{0, 0}, hi{0, 0}, period{0, 0};
  };
  const Range& range(int dim, int tag) const;

  // The point of the entity at the parameters of g.
  Point value(const GeoParam& g) const;
  // The derivatives of a surface at (u, v): d/du and d/dv.
  std::array<Eigen::Vector3d, 2> derivatives(int surface, double u, double v) const;
  // The unit normal of a surface at (u, v) (gmsh's orientation).
  Eigen::Vector3d normal(int surface, double u, double v) const;
  // The principal curvatures of a surface at (u, v) (1/length; signs as
  // gmsh gives them) and their unit directions, tangent to the surface.
  struct Curvatures {
    double max = 0, min = 0;
    Eigen::Vector3d max_direction = Eigen::Vector3d::Zero(), min_direction = Eigen::Vector3d::Zero();
  };
  Curvatures principal_curvatures(int surface, double u, double v) const;
  // The parameters of point p on entity (dim, tag) by projection (a
  // search: costly on B-spline surfaces; used to associate a mesh once).
  GeoParam parametrize(int dim, int tag, const Point& p) const;
  // The (u, v) of g's point on surface s, g being on s or on a curve or
  // model vertex of s's boundary; on a periodic surface the period shift
  // nearest `near` (when given).
  std::array<double, 2> on_surface(const GeoParam& g, int surface, const std::array<double, 2>* near = nullptr) const;
  // The t of g's point on curve c (g on c or one of its end vertices),
  // the representative nearest `near` when given.
  double on_curve(const GeoParam& g, int curve, const double* near = nullptr) const;

 private:
  void sew_into_volume();
  void read_topology();
  std::string source_;
  double size_ = 1.0;
  std::array<std::vector<int>, 4> entities_;
  std::map<int, std::vector<int>> curves_of_surface_, vertices_of_curve_, curves_of_vertex_, surfaces_of_curve_;
  std::map<std::pair<int, int>, Range> ranges_;
  mutable std::mutex lock_;
};

}  // namespace metrica
