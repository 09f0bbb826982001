// The box generator and compaction (renumbering for locality).
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

using namespace metrica;

TEST_SUITE("unit") {
  TEST_CASE("box counts and volume and n = 3 is the UGAWG start mesh") {
    const auto d = box_mesh_data({});
    CHECK(d.vertices.size() == 64);
    CHECK(d.tets.size() == 162);
    CHECK(d.triangles.size() == 108);
    const auto mesh = build_mesh(d);
    CHECK(mesh.validate({.expected_volume = 1.0}).ok());
    // Same surface id convention as cube-linear-00: compare id areas.
    const auto ours = summarize(mesh),
               theirs = summarize(build_mesh(io::read_meshb(test::ugawg("cube-linear-00.meshb"))));
    CHECK(ours.surfaces.size() == theirs.surfaces.size());
    for (const auto& [id, s] : ours.surfaces) CHECK(theirs.surfaces.at(id).faces == s.faces);
    const auto big = make_box({.nx = 7, .ny = 5, .nz = 3, .lo = Point(0, 0, 0), .hi = Point(7, 5, 3)});
    CHECK(big.num_tets() == 6u * 7 * 5 * 3);
    CHECK(big.volume() == doctest::Approx(105.0).epsilon(1e-14));
    CHECK(big.validate().ok());
  }

  TEST_CASE("box: surface ids sit on their sides") {
    const auto mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      for (int f = 0; f < 4; ++f) {
        if (mesh.neighbour(t, f).valid()) continue;
        const auto tri = face_vertices(mesh.tet(t), f);
        const int id = mesh.surface_id(t, f);
        const int axis = (id - 1) / 2;
        const double side = (id - 1) % 2 == 0 ? 0.0 : 1.0;
        for (VertexId v : tri) CHECK(mesh.point(v)[axis] == side);
      }
  }

  TEST_CASE("bad box specifications are errors") {
    CHECK_THROWS(make_box({.nx = 0}));
    CHECK_THROWS(make_box({.nx = 1, .ny = 1, .nz = 1, .lo = Point(0, 0, 0), .hi = Point(1, 0, 1)}));
  }

  TEST_CASE("compact after deletions keeps the mesh valid and drops dead entities") {
    auto mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    const double volume = mesh.volume();
    const auto before = summarize(mesh);
    // Simulate an operator's leftovers: a tet and a vertex added then removed.
    const VertexId v = mesh.add_vertex(Point(0.5, 0.5, 0.5));
    const TetId t = mesh.add_tet({0, 1, 2, v});
    mesh.remove_tet(t);
    mesh.remove_vertex(v);
    CHECK(mesh.tet_capacity() == mesh.num_tets() + 1);
    mesh.compact();
    CHECK(mesh.tet_capacity() == mesh.num_tets());
    CHECK(mesh.vertex_capacity() == mesh.num_vertices());
    CHECK(mesh.validate({.expected_volume = volume}).ok());
    const auto after = summarize(mesh);
    CHECK(after.corners == before.corners);
    CHECK(after.ridge_edges == before.ridge_edges);
    CHECK(after.ridge_curves == 12);
  }

  TEST_CASE("compact orders vertices along a space-filling curve") {
    auto mesh = make_box({.nx = 8, .ny = 8, .nz = 8});
    // Median over tets of the id range of their vertices: with x-fastest
    // numbering every tet spans two z-planes (>= 81 ids); along the Morton
    // curve most tets lie inside a small block.
    auto median_tet_span = [&] {
      std::vector<VertexId> spans;
      for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
        const auto& v = mesh.tet(t);
        spans.push_back(*std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end()));
      }
      std::nth_element(spans.begin(), spans.begin() + spans.size() / 2, spans.end());
      return spans[spans.size() / 2];
    };
    const auto lexicographic = median_tet_span();
    CHECK(lexicographic >= 81);
    mesh.compact();
    CHECK(mesh.validate().ok());
    CHECK(median_tet_span() < lexicographic / 2);
    // Compaction is deterministic.
    auto other = make_box({.nx = 8, .ny = 8, .nz = 8});
    other.compact();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) CHECK(mesh.tet(t) == other.tet(t));
  }
}
