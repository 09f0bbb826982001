// Point creation by centroids (refine_centroids.hpp) and its insertions
// (split_cell.hpp), under every policy combination: after every pass the
// mesh is valid with its volume and boundary areas, and new points land
// inside tets, on boundary faces and on ridges as the encroachment rules
// say.
#include "operator_test_support.hpp"

#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/operators/reconnect.hpp>
#include <metrica/operators/refine_centroids.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>

using namespace metrica;
using namespace metrica::test;

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("centroid insertion keeps the mesh valid and puts points inside and on the boundary", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using P = typename T::Precision;
    using C = typename T::Concurrency;
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    set_uniform_metric(mesh, 0.2);
    const auto areas = surface_areas(mesh);
    const std::size_t ridges = mesh.ridge_edges().size();
    std::size_t inserted = 0;
    for (int pass = 0; pass < 4; ++pass) {
      const auto st = refine_centroids<S, C>(mesh);
      if (T::Concurrency::threads() == 1) CHECK(st.conflicts == 0);  // conflicts need two threads
      inserted += st.applied;
      require_valid(mesh, 1.0);
      reconnect<S, C, MetricDelaunay<P>>(mesh);
      require_valid(mesh, 1.0);
    }
    CHECK(inserted > 50);
    int by_class[4] = {0, 0, 0, 0};
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      if (!mesh.vertex_alive(v)) continue;
      ++by_class[static_cast<int>(mesh.vertex_class(v))];
      // Every vertex lies in the closed box, on its faces by its class.
      const Point& p = mesh.point(v);
      int on_faces = 0;
      for (int k = 0; k < 3; ++k) {
        CHECK(p[k] >= 0.0);
        CHECK(p[k] <= 1.0);
        on_faces += (std::abs(p[k]) < 1e-12 || std::abs(p[k] - 1.0) < 1e-12);
      }
      if (mesh.vertex_class(v) == VertexClass::interior) CHECK(on_faces == 0);
      if (mesh.vertex_class(v) == VertexClass::surface) CHECK(on_faces == 1);
      if (mesh.vertex_class(v) == VertexClass::ridge) CHECK(on_faces == 2);
    }
    CHECK(by_class[0] > 1);                     // centroids inside
    CHECK(by_class[1] > 0);                     // encroached boundary faces
    CHECK(mesh.ridge_edges().size() > ridges);  // encroached ridges were split
    CHECK(by_class[3] == 8);
    const auto after = surface_areas(mesh);
    REQUIRE(after.size() == areas.size());
    for (const auto& [id, area] : areas) CHECK(after.at(id) == doctest::Approx(area).epsilon(1e-12));
  }

  TEST_CASE_TEMPLATE("a tet split in four and a boundary face split in three conserve volume and area", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    set_uniform_metric(mesh, 1.0);
    const auto areas = surface_areas(mesh);
    const std::size_t tets = mesh.num_tets();
    CellSplitScratch s;
    const VertexMetric m{isotropic_metric(1.0), spd_log(isotropic_metric(1.0))};
    // Inside tet 0, at its centroid.
    const auto& v0 = mesh.tet(0);
    const Point c = 0.25 * (mesh.point(v0[0]) + mesh.point(v0[1]) + mesh.point(v0[2]) + mesh.point(v0[3]));
    REQUIRE(cell_split_is_valid(mesh, 0, -1, c));
    const VertexId n = split_cell(mesh, 0, -1, c, m, s);
    REQUIRE(n != kNoId);
    CHECK(mesh.vertex_class(n) == VertexClass::interior);
    CHECK(mesh.num_tets() == tets + 3);
    require_valid(mesh, 1.0);
    // A boundary face of some tet, at its centroid.
    bool done = false;
    for (TetId t = 0; t < mesh.tet_capacity() && !done; ++t) {
      if (!mesh.tet_alive(t)) continue;
      for (int f = 0; f < 4 && !done; ++f) {
        if (mesh.neighbour(t, f).valid()) continue;
        const auto fv = face_vertices(mesh.tet(t), f);
        const Point p = (mesh.point(fv[0]) + mesh.point(fv[1]) + mesh.point(fv[2])) / 3.0;
        CHECK_FALSE(cell_split_is_valid(mesh, t, -1, p));  // on a face: flat as an inside split
        REQUIRE(cell_split_is_valid(mesh, t, f, p));
        const VertexId b = split_cell(mesh, t, f, p, m, s);
        REQUIRE(b != kNoId);
        CHECK(mesh.vertex_class(b) == VertexClass::surface);
        done = true;
      }
    }
    REQUIRE(done);
    CHECK(mesh.num_tets() == tets + 5);
    require_valid(mesh, 1.0);
    const auto after = surface_areas(mesh);
    for (const auto& [id, area] : areas) CHECK(after.at(id) == doctest::Approx(area).epsilon(1e-14));
  }

  TEST_CASE("centroid insertion on the cube-cylinder keeps ridges and surface ids") {
    Mesh mesh = build_mesh(io::read_meshb(test::ugawg("cube-cylinder.meshb")));
    const double volume = mesh.volume();
    set_uniform_metric(mesh, 0.08);
    const auto ids = surface_areas(mesh).size();
    for (int pass = 0; pass < 3; ++pass) {
      refine_centroids<LogEuclidean, Serial>(mesh);
      require_valid(mesh, volume);
      reconnect<LogEuclidean, Serial, MetricDelaunay<Filtered>>(mesh);
      require_valid(mesh, volume);
    }
    CHECK(surface_areas(mesh).size() == ids);
  }
}

TEST_SUITE("property") {
  TEST_CASE("the diametral sphere test: the circumcentre encroaches and a far point does not") {
    const Point a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    const Matrix3 id = Matrix3::Identity();
    CHECK(detail::encroaches_face(id, Point(0.5, 0.5, 0.1), a, b, c));
    CHECK_FALSE(detail::encroaches_face(id, Point(0.5, 0.5, 0.8), a, b, c));
    // Stretching z by 10 in the metric pushes the same point out.
    Matrix3 l = id;
    l(2, 2) = 10.0;
    CHECK_FALSE(detail::encroaches_face(l, Point(0.5, 0.5, 0.1), a, b, c));
  }
}

TEST_SUITE("regression") {
  TEST_CASE("adapting with the centroid rule: a valid unit mesh for a constant metric") {
    Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    set_uniform_metric(mesh, 0.15);
    AdaptOptions o;
    o.points = PointRule::centroid;
    const auto report = adapt_by_name(mesh, o, {.concurrency = "serial"});
    require_valid(mesh, 1.0);
    const auto& last = report.cycles.back();
    INFO("conformity " << last.conformity << " min Q " << last.min_quality);
    CHECK(last.conformity >= 0.85);
    CHECK(last.min_quality >= 0.2);
  }
}
