// Building a Mesh from raw arrays: adjacency, boundary tags, and the
// clear errors on input that is not a valid tet mesh.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

using namespace metrica;

namespace {

// Two tets sharing the face (1 2 3): 0 below, 4 above.
io::MeshData two_tets() {
  io::MeshData d;
  d.vertices = {Point(0, 0, -1), Point(1, 0, 0), Point(0, 1, 0), Point(-1, -1, 0), Point(0, 0, 1)};
  d.tets = {{0, 1, 2, 3}, {4, 1, 3, 2}};
  test::orient_positively(d);
  return d;
}

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("two tets: the shared face is linked both ways - the others are boundary") {
    test::QuietLog quiet;  // no triangles given: default ids, with a warning
    BuildOptions as_given;
    as_given.ridge_angle = 180.0;  // not split by angle (test_surface_angles.cpp)
    const auto mesh = build_mesh(two_tets(), as_given);
    CHECK(mesh.num_tets() == 2);
    int links = 0, boundary = 0;
    for (TetId t = 0; t < 2; ++t)
      for (int f = 0; f < 4; ++f) {
        const auto n = mesh.neighbour(t, f);
        if (n.valid()) {
          ++links;
          CHECK(n.tet() == 1 - t);
          CHECK(mesh.neighbour(n) == FaceRef(t, f));
        } else {
          ++boundary;
          CHECK(mesh.surface_id(t, f) == 1);  // default: max input id (0) + 1
        }
      }
    CHECK(links == 2);
    CHECK(boundary == 6);
    CHECK(mesh.validate().ok());
  }

  TEST_CASE("triangles tag their faces - untagged faces get the default id") {
    test::QuietLog quiet;
    auto d = two_tets();
    d.triangles = {{0, 1, 2}};
    d.triangle_refs = {7};
    const auto mesh = build_mesh(d, BuildOptions{.default_surface_id = 3, .ridge_angle = 180.0, .source = "t"});
    std::map<SurfaceId, int> ids;
    for (TetId t = 0; t < 2; ++t)
      for (int f = 0; f < 4; ++f)
        if (!mesh.neighbour(t, f).valid()) ++ids[mesh.surface_id(t, f)];
    CHECK(ids[7] == 1);
    CHECK(ids[3] == 5);
  }

  TEST_CASE("a face's word holds its neighbour or its surface id, never both") {
    for (SurfaceId id : {0, 1, 7, 4096, kMaxSurfaceId}) {
      const FaceRef b = FaceRef::boundary(id);
      CHECK_FALSE(b.valid());
      CHECK(b.surface() == id);
    }
    CHECK(FaceRef::none() == FaceRef::boundary(0));
    for (TetId t : {TetId{0}, TetId{5}, static_cast<TetId>(kMaxTets - 1)})
      for (int f = 0; f < 4; ++f) {
        const FaceRef n(t, f);
        CHECK(n.valid());
        CHECK(n.tet() == t);
        CHECK(n.face() == f);
        CHECK(n.surface() == 0);
      }
  }

  TEST_CASE("a surface id beyond those a mesh holds is an error naming it") {
    auto d = two_tets();
    d.triangles = {{0, 1, 2}};
    d.triangle_refs = {kMaxSurfaceId + 1};
    CHECK_THROWS_WITH_AS(build_mesh(d, BuildOptions{.source = "big.mesh"}),
                         doctest::Contains("big.mesh: surface id 268435456 is beyond the ids a mesh holds"),
                         InputError);
  }

  TEST_CASE("every tet negatively oriented: all are reoriented") {
    test::QuietLog quiet;
    auto d = two_tets();
    for (auto& t : d.tets) std::swap(t[0], t[1]);
    const auto mesh = build_mesh(d);
    CHECK(mesh.validate().ok());
    CHECK(mesh.volume() > 0);
  }

  TEST_CASE("an inverted tet among positive ones is an error naming it") {
    auto d = two_tets();
    std::swap(d.tets[1][0], d.tets[1][1]);
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("tet 2 (vertices"), InputError);
  }

  TEST_CASE("a degenerate (flat) tet is an error") {
    auto d = two_tets();
    d.vertices[4] = Point(0.2, 0.2, 0);  // on the plane of face (1 2 3)
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("degenerate"), InputError);
    auto e = two_tets();
    e.tets[0][1] = e.tets[0][0];
    CHECK_THROWS_AS(build_mesh(e), InputError);
  }

  TEST_CASE("a triangle that is no tet face is an error") {
    auto d = two_tets();
    d.triangles = {{0, 4, 1}};
    d.triangle_refs = {1};
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("is not a face of any tetrahedron"), InputError);
    // A triangle with a repeated vertex (found by the readers' fuzzer).
    for (const TriangleVertices& bad :
         {TriangleVertices{0, 0, 1}, TriangleVertices{1, 2, 1}, TriangleVertices{3, 3, 3}}) {
      d.triangles = {bad};
      CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("is not a face of any tetrahedron"), InputError);
    }
  }

  TEST_CASE("a face shared by three tets is an error") {
    auto d = two_tets();
    d.vertices.push_back(Point(0.1, 0.1, 2));
    d.tets.push_back(d.tets[1]);
    d.tets.back()[0] = 5;
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("shared by more than two"), InputError);
  }

  TEST_CASE("no tets or vertices outside every tet") {
    io::MeshData d;
    d.vertices = {Point(0, 0, 0)};
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("no tetrahedra"), InputError);
    test::QuietLog quiet;
    auto e = two_tets();
    e.vertices.push_back(Point(5, 5, 5));  // isolated: dropped
    const auto mesh = build_mesh(e);
    CHECK(mesh.num_vertices() == 5);
    CHECK(mesh.validate().ok());
  }

  TEST_CASE("extract_mesh_data then build gives the same mesh") {
    const auto mesh = build_mesh(io::read_meshb(test::ugawg("cube-cylinder.meshb")));
    const auto d = extract_mesh_data(mesh);
    CHECK(d.tets.size() == 952);
    CHECK(d.triangles.size() == 418);
    const auto again = build_mesh(d);
    CHECK(again.validate().ok());
    CHECK(again.ridge_edges().size() == mesh.ridge_edges().size());
    CHECK(again.volume() == doctest::Approx(mesh.volume()).epsilon(1e-15));
    // Boundary triangles come out oriented outwards: their signed volume
    // against the centroid is negative.
    Point c = Point::Zero();
    for (const auto& p : d.vertices) c += p;
    c /= double(d.vertices.size());
    const auto d2 = extract_mesh_data(build_mesh(io::read_meshb(test::ugawg("cube-linear-00.meshb"))));
    for (const auto& t : d2.triangles) {
      const Point &a = d2.vertices[t[0]], &b = d2.vertices[t[1]], &cc = d2.vertices[t[2]];
      CHECK((b - a).cross(cc - a).dot(Point(0.5, 0.5, 0.5) - a) < 0);
    }
  }
}
