// Ridges and corners: the cube's 12 ridges and 8 corners, the
// cube-cylinder's curved ridges, feature edges and required vertices.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/classification.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>

#include <doctest/doctest.h>

using namespace metrica;

TEST_SUITE("unit") {
  TEST_CASE("box: 12 ridge curves - 8 corners - for several resolutions") {
    for (int n : {1, 2, 3, 5}) {
      const auto mesh = make_box({.nx = n, .ny = n + 1, .nz = 2});
      const auto s = summarize(mesh);
      CAPTURE(n);
      CHECK(s.ridge_curves == 12);
      CHECK(s.corners == 8);
      CHECK(s.ridge_edges == std::size_t(4 * (n + (n + 1) + 2)));
      CHECK(s.ridge_vertices == std::size_t(4 * ((n - 1) + n + 1)));
      CHECK(s.surfaces.size() == 6);
    }
  }

  TEST_CASE("a corner of the cube is a corner - an edge midpoint a ridge vertex - a face centre a surface vertex") {
    const auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    auto vertex_at = [&](Point p) {
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
        if ((mesh.point(v) - p).norm() < 1e-12) return v;
      return kNoId;
    };
    CHECK(mesh.vertex_class(vertex_at(Point(0, 0, 0))) == VertexClass::corner);
    CHECK(mesh.vertex_class(vertex_at(Point(0.5, 0, 0))) == VertexClass::ridge);
    CHECK(mesh.vertex_class(vertex_at(Point(0.5, 0.5, 0))) == VertexClass::surface);
    CHECK(mesh.vertex_class(vertex_at(Point(0.5, 0.5, 0.5))) == VertexClass::interior);
    CHECK(mesh.is_ridge(vertex_at(Point(0, 0, 0)), vertex_at(Point(0.5, 0, 0))));
    CHECK_FALSE(mesh.is_ridge(vertex_at(Point(0, 0, 0)), vertex_at(Point(0.5, 0.5, 0))));
  }

  TEST_CASE("UGAWG cube-linear-00 and cube-cylinder") {
    const auto cube = summarize(build_mesh(io::read_meshb(test::ugawg("cube-linear-00.meshb"))));
    CHECK(cube.ridge_curves == 12);
    CHECK(cube.corners == 8);
    // The cylinder cut out of the cube: 7 surface ids (the cylinder in two
    // halves), ridges between all of them; the .mesh (no Edges keyword)
    // and the .meshb (62 Edges) classify alike.
    const auto a = summarize(build_mesh(io::read_meshb(test::ugawg("cube-cylinder.mesh"))));
    const auto b = summarize(build_mesh(io::read_meshb(test::ugawg("cube-cylinder.meshb"))));
    CHECK(a.surfaces.size() == 7);
    CHECK(a.ridge_edges == 62);
    CHECK(a.corners == 10);
    CHECK(a.ridge_curves == 15);
    CHECK(b.ridge_edges == a.ridge_edges);
    CHECK(b.corners == a.corners);
  }

  TEST_CASE("in parts the classification is the same (cube-cylinder)") {
    const Mesh mesh = build_mesh(io::read_meshb(test::ugawg("cube-cylinder.meshb")));
    const Classification one = compute_classification(mesh);
    for (std::size_t parts : {2, 3, 5}) {
      const Classification c = compute_classification(mesh, PartRunner{parts, {}});
      CHECK(c.vertex_class == one.vertex_class);
      CHECK(c.ridges == one.ridges);
      CHECK(c.on_internal_surface == one.on_internal_surface);
    }
  }

  TEST_CASE("a vertex's class from the triangles around it alone is the mesh's (cube-cylinder, a box)") {
    for (const auto& d :
         {io::read_meshb(test::ugawg("cube-cylinder.mesh")), box_mesh_data({.nx = 3, .ny = 2, .nz = 2})}) {
      const auto mesh = build_mesh(d);
      std::vector<std::vector<FanSide>> fans(d.vertices.size());
      for (std::size_t i = 0; i < d.triangles.size(); ++i)
        for (int c = 0; c < 3; ++c)
          for (int k : {1, 2})
            fans[d.triangles[i][std::size_t(c)]].push_back(
                {std::int64_t(d.triangles[i][std::size_t((c + k) % 3)]), d.triangle_refs[i]});
      std::size_t corners = 0, ridges = 0;
      for (VertexId v = 0; v < d.vertices.size(); ++v) {
        CAPTURE(v);
        const VertexClass c = vertex_class_of_fan(fans[v]);
        CHECK(c == mesh.vertex_class(v));
        corners += c == VertexClass::corner;
        ridges += c == VertexClass::ridge;
      }
      CHECK(corners >= 8);
      CHECK(ridges > 0);
    }
  }

  TEST_CASE("feature edges and required vertices from the input") {
    auto d = box_mesh_data({.nx = 2, .ny = 2, .nz = 2});
    // A feature edge across the middle of face z = 0 (same surface id on
    // both sides): from (0, .5, 0) to (.5, .5, 0) to (1, .5, 0).
    auto id = [](int i, int j, int k) { return VertexId(i + 3 * (j + 3 * k)); };
    d.edges = {{id(0, 1, 0), id(1, 1, 0)}, {id(1, 1, 0), id(2, 1, 0)}};
    d.edge_refs = {0, 0};
    d.required_vertices = {id(1, 1, 2)};  // centre of the top face
    const auto mesh = build_mesh(d);
    CHECK(mesh.is_ridge(id(0, 1, 0), id(1, 1, 0)));
    CHECK(mesh.vertex_class(id(1, 1, 0)) == VertexClass::ridge);
    CHECK(mesh.vertex_class(id(1, 1, 2)) == VertexClass::corner);
    CHECK(mesh.is_required(id(1, 1, 2)));
    // The feature's ends lie on the cube's ridges: 3 ridge edges there.
    CHECK(mesh.vertex_class(id(0, 1, 0)) == VertexClass::corner);
    CHECK(summarize(mesh).ridge_curves == 12 + 2 + 1);  // two cube ridges split in two, plus the feature
  }
}
