// validate(): valid meshes pass; each invariant, broken on purpose, is
// caught by its own check with a message that names the culprit.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

using namespace metrica;

namespace {

bool only(const ValidationReport& r, const std::string& check) {
  return r.count(check) > 0 && r.count(check) == r.total();
}

}  // namespace

TEST_SUITE("invariant") {
  TEST_CASE("UGAWG meshes and boxes are valid") {
    for (const char* name : {"cube-linear-00.meshb", "cube-cylinder.meshb", "cone-cone.meshb"}) {
      const auto r = build_mesh(io::read_meshb(test::ugawg(name))).validate();
      CHECK_MESSAGE(r.ok(), name, "\n", r.to_string());
    }
    const auto box = make_box({.nx = 4, .ny = 3, .nz = 2, .lo = Point(-1, 0, 2), .hi = Point(3, 1, 2.5)});
    CHECK(box.validate({.expected_volume = 4.0 * 1.0 * 0.5}).ok());
  }

  TEST_CASE("orientation: moving a vertex through its opposite face") {
    auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    // The centre vertex, pushed far out, inverts tets around it.
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      if ((mesh.point(v) - Point(0.5, 0.5, 0.5)).norm() < 1e-12) mesh.point(v) = Point(0.5, 0.5, 5.0);
    const auto r = mesh.validate();
    CHECK(only(r, "orientation"));
    CHECK(r.problems().front().message.find("orient3d") != std::string::npos);
  }

  TEST_CASE("adjacency: a slot that does not point back") {
    auto mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    for (int f = 0; f < 4; ++f)
      if (mesh.neighbour(0, f).valid()) {
        const auto n = mesh.neighbour(0, f);
        mesh.set_neighbour(n.tet(), n.face(), FaceRef(n.tet() == 1 ? 2 : 1, 0));
        break;
      }
    CHECK(mesh.validate().count("adjacency") > 0);
  }

  TEST_CASE("boundary: a boundary face without a surface id - an interior face given one") {
    auto mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    for (int f = 0; f < 4; ++f)
      if (!mesh.neighbour(0, f).valid()) {
        mesh.set_surface_id(0, f, 0);
        break;
      }
    auto r = mesh.validate();
    CHECK(r.count("boundary") == 1);
    // One word holds a face's neighbour or its surface id: an interior
    // face given an id has lost its neighbour on that side only.
    auto mesh2 = make_box({.nx = 1, .ny = 1, .nz = 1});
    for (int f = 0; f < 4; ++f)
      if (mesh2.neighbour(0, f).valid()) {
        mesh2.set_surface_id(0, f, 4);
        CHECK(mesh2.surface_id(0, f) == 4);
        CHECK_FALSE(mesh2.neighbour(0, f).valid());
        break;
      }
    r = mesh2.validate();
    CHECK(r.count("adjacency") == 1);
    CHECK(r.problems().front().message.find("does not point back") != std::string::npos);
  }

  TEST_CASE("manifold: two tets touching along an edge only - and at a vertex only") {
    test::QuietLog quiet;
    io::MeshData edge;
    edge.vertices = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1), Point(0, -1, 0), Point(0, 0, -1)};
    edge.tets = {{0, 1, 2, 3}, {0, 1, 5, 4}};  // share the edge (0 1)
    test::orient_positively(edge);
    auto r = build_mesh(edge).validate();
    CHECK(r.count("manifold") >= 1);
    CHECK(r.problems().front().message.find("lies on 4 boundary faces") != std::string::npos);

    io::MeshData vertex;
    vertex.vertices = {Point(0, 0, 0),  Point(1, 0, 0),  Point(0, 1, 0), Point(0, 0, 1),
                       Point(-1, 0, 0), Point(0, -1, 0), Point(0, 0, -1)};
    vertex.tets = {{0, 1, 2, 3}, {0, 4, 6, 5}};  // share vertex 0
    test::orient_positively(vertex);
    r = build_mesh(vertex).validate();
    CHECK(only(r, "manifold"));
    CHECK(r.problems().front().message.find("single umbrella") != std::string::npos);
  }

  TEST_CASE("faces: two pairs of neighbours on one triangle (their adjacency consistent pair by pair)") {
    test::QuietLog quiet;
    // Two copies of the pair (0 1 2 3), (0 2 1 4), the second on its own
    // vertices 5..9, then made to use 0 1 2 as the first pair does.
    io::MeshData d;
    d.vertices = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0.2, 0.2, 1), Point(0.2, 0.2, -1)};
    for (int k = 0; k < 5; ++k) d.vertices.push_back(d.vertices[k] + Point(3, 0, 0));
    d.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}, {5, 6, 7, 8}, {5, 7, 6, 9}};
    test::orient_positively(d);
    Mesh mesh = build_mesh(d);
    REQUIRE(mesh.validate().ok());
    mesh.point(8) = Point(0.3, 0.2, 1);
    mesh.point(9) = Point(0.3, 0.2, -1);
    for (TetId t : {TetId(2), TetId(3)}) {
      TetVertices v = mesh.tet(t);
      for (auto& x : v)
        if (x >= 5 && x <= 7) x -= 5;
      mesh.set_tet_vertices(t, v);
    }
    const auto r = mesh.validate();
    CHECK(r.count("faces") == 1);
    CHECK(r.to_string().find("triangle (1 2 3) is a face of more than two tets") != std::string::npos);
    // In parts, as adapt's checks run it: the same report.
    for (std::size_t parts : {2, 3, 7}) {
      ValidateOptions o;
      o.run = PartRunner{parts, {}};
      CHECK(mesh.validate(o).to_string() == r.to_string());
    }
  }

  TEST_CASE("classification: a surface id changed without reclassifying") {
    auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      for (int f = 0; f < 4; ++f)
        if (!mesh.neighbour(t, f).valid() && mesh.surface_id(t, f) == 5) {
          mesh.set_surface_id(t, f, 9);
          CHECK(only(mesh.validate(), "classification"));
          mesh.classify();
          CHECK(mesh.validate().ok());
          return;
        }
    FAIL("no face with surface id 5");
  }

  TEST_CASE("vert2tet: a hint to a tet that does not hold the vertex") {
    auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    const TetId t = mesh.vert2tet(0);
    for (TetId u = 0; u < mesh.tet_capacity(); ++u)
      if (local_index(mesh.tet(u), 0) < 0) {
        mesh.set_vert2tet(0, u);
        break;
      }
    CHECK(only(mesh.validate(), "vert2tet"));
    mesh.set_vert2tet(0, t);
    CHECK(mesh.validate().ok());
  }

  TEST_CASE("vertices: a tet naming a dead vertex stops the later checks") {
    auto mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    mesh.remove_vertex(mesh.tet(0)[0]);
    const auto r = mesh.validate();
    CHECK(only(r, "vertices"));
  }

  TEST_CASE("volume: compared with the expected one") {
    const auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    CHECK(mesh.validate({.expected_volume = 1.0}).ok());
    const auto r = mesh.validate({.expected_volume = 1.001});
    CHECK(only(r, "volume"));
  }

  TEST_CASE("the report caps messages per check - not counts") {
    auto mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) mesh.point(v) *= -1.0;  // every tet inverted
    const auto r = mesh.validate({.max_messages_per_check = 3});
    CHECK(r.count("orientation") == mesh.num_tets());
    CHECK(r.problems().size() == 3);
    CHECK(r.to_string().find("162 orientation") != std::string::npos);
  }
}
