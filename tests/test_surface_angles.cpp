// Surfaces and ridges by angle (surface_angles.hpp): a boundary given
// without surface ids, or with one id for all of it, is split at the edges
// sharper than the ridge angle; the box keeps its 6 faces, 12 ridge
// curves and 8 corners, a smooth surface is not split, 180 degrees splits
// nothing, and ids given by the input stay unless every surface is split.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>
#include <metrica/surface_angles.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace metrica;

namespace {

// The box's points and tets, its triangles dropped or given one id.
io::MeshData box_data(bool triangles_with_one_id) {
  io::MeshData d = extract_mesh_data(make_box({.nx = 3, .ny = 4, .nz = 2}));
  d.edges.clear();
  d.ridges.clear();
  d.corners.clear();
  if (triangles_with_one_id) {
    d.triangle_refs.assign(d.triangles.size(), 7);
  } else {
    d.triangles.clear();
    d.triangle_refs.clear();
  }
  return d;
}

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("a box of points and tets: 6 surfaces, 12 ridge curves, 8 corners, its volume") {
    for (const bool one_id : {false, true}) {
      CAPTURE(one_id);
      const Mesh mesh = build_mesh(box_data(one_id));
      const auto s = summarize(mesh);
      CHECK(s.surfaces.size() == 6);
      CHECK(s.ridge_curves == 12);
      CHECK(s.ridge_edges == std::size_t(4 * (3 + 4 + 2)));
      CHECK(s.corners == 8);
      CHECK(std::abs(s.volume - 1.0) < 1e-12);
      CHECK(mesh.validate().ok());
      if (one_id) CHECK(s.surfaces.count(7) == 1);  // the first piece keeps the given id
    }
  }

  TEST_CASE("180 degrees splits nothing; nor does an angle above the box's right angles") {
    for (const double angle : {180.0, 100.0}) {
      BuildOptions o;
      o.ridge_angle = angle;
      const auto s = summarize(build_mesh(box_data(false), o));
      CHECK(s.surfaces.size() == 1);
      CHECK(s.ridge_edges == 0);
      CHECK(s.corners == 0);
    }
  }

  TEST_CASE("ids given by the input stay; split_every_surface splits them too") {
    // The box with its own six ids: nothing to split at 45 degrees.
    io::MeshData d = extract_mesh_data(make_box({.nx = 2, .ny = 2, .nz = 2}));
    const auto before = summarize(build_mesh(d));
    // One pair of faces given one id: a surface of two planes at 90 degrees.
    for (std::size_t i = 0; i < d.triangles.size(); ++i)
      if (d.triangle_refs[i] == 2) d.triangle_refs[i] = 1;
    d.edges.clear();
    d.ridges.clear();
    d.corners.clear();
    const auto merged = summarize(build_mesh(d));
    CHECK(merged.surfaces.size() == 5);
    BuildOptions every;
    every.split_every_surface = true;
    const auto split = summarize(build_mesh(d, every));
    CHECK(split.surfaces.size() == 6);
    CHECK(split.ridge_curves == before.ridge_curves);
    CHECK(split.corners == before.corners);
  }

  TEST_CASE("a smooth surface is not split; a sharp edge inside one surface is a ridge") {
    // A cylinder of 24 sectors about z: its side turns by 15 degrees an
    // edge, its rims by 90. Built as a prism mesh of the sectors.
    io::MeshData d;
    const int n = 24;
    d.vertices.push_back(Point(0, 0, 0));
    d.vertices.push_back(Point(0, 0, 1));
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      d.vertices.push_back(Point(std::cos(a), std::sin(a), 0));
      d.vertices.push_back(Point(std::cos(a), std::sin(a), 1));
    }
    for (int k = 0; k < n; ++k) {
      const VertexId b0 = 2 + 2 * k, t0 = b0 + 1, b1 = 2 + 2 * ((k + 1) % n), t1 = b1 + 1;
      // The prism (0, b0, b1 | 1, t0, t1) in three tets.
      for (const TetVertices& t : {TetVertices{0, b0, b1, 1}, TetVertices{1, b0, b1, t1}, TetVertices{1, b0, t1, t0}})
        d.tets.push_back(t);
    }
    d.tet_refs.assign(d.tets.size(), 1);
    d.vertex_refs.assign(d.vertices.size(), 0);
    for (auto& t : d.tets) {
      const Point& p0 = d.vertices[t[0]];
      const double v = (d.vertices[t[1]] - p0).cross(d.vertices[t[2]] - p0).dot(d.vertices[t[3]] - p0);
      if (v < 0) std::swap(t[2], t[3]);
    }
    const auto s = summarize(build_mesh(d));
    CHECK(s.surfaces.size() == 3);               // bottom, top, side
    CHECK(s.ridge_edges == std::size_t(2 * n));  // the two rims
    CHECK(s.ridge_curves == 2);
    CHECK(s.corners == 0);
  }
}
