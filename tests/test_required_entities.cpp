// Required entities and the kept surface:
//   - RequiredVertices, RequiredEdges and RequiredTriangles are read and
//     written (.mesh and .meshb), their indices checked;
//   - adapted (refined and coarsened) under every policy, each required
//     vertex, edge and triangle is in the output where it was;
//   - with keep_surface() the surface comes out as it went in while the
//     volume is refined;
//   - a required edge that is not an edge of the mesh is an input error.
#include "operator_test_support.hpp"

#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/pipeline/adapt.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <set>

using namespace metrica;
using namespace metrica::test;

namespace {

using Coords = std::array<double, 3>;
using Edge = std::array<Coords, 2>;
using Triangle = std::array<Coords, 3>;

Coords coords(const Point& p) { return {p.x(), p.y(), p.z()}; }

template <std::size_t N>
std::array<Coords, N> sorted_corners(const io::MeshData& d, const std::array<VertexId, N>& ids) {
  std::array<Coords, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = coords(d.vertices[ids[i]]);
  std::sort(out.begin(), out.end());
  return out;
}

// What the file says is required, by coordinates.
struct Required {
  std::set<Coords> vertices;
  std::set<Edge> edges;
  std::set<Triangle> triangles;
  explicit Required(const io::MeshData& d) {
    for (VertexId v : d.required_vertices) vertices.insert(coords(d.vertices[v]));
    for (auto e : d.required_edges) edges.insert(sorted_corners(d, d.edges[e]));
    for (auto t : d.required_triangles) triangles.insert(sorted_corners(d, d.triangles[t]));
  }
};

// Every surface triangle, by coordinates.
std::set<Triangle> surface_triangles(const io::MeshData& d) {
  std::set<Triangle> out;
  for (const auto& t : d.triangles) out.insert(sorted_corners(d, t));
  return out;
}

// The 4x4x4 box with required triangles (the boundary triangles of x = 0
// with y <= 0.5), a required edge on z = 0 and a required vertex on y = 1.
io::MeshData box_with_required() {
  io::MeshData d = extract_mesh_data(make_box({.nx = 4, .ny = 4, .nz = 4}));
  for (std::size_t i = 0; i < d.triangles.size(); ++i) {
    const auto& t = d.triangles[i];
    const bool on_x0 = std::all_of(t.begin(), t.end(), [&](VertexId v) { return d.vertices[v].x() == 0.0; });
    const bool low = std::all_of(t.begin(), t.end(), [&](VertexId v) { return d.vertices[v].y() <= 0.5; });
    if (on_x0 && low) d.required_triangles.push_back(static_cast<std::uint32_t>(i));
  }
  // An edge of a boundary triangle on z = 0, away from x = 0.
  for (const auto& t : d.triangles) {
    if (!std::all_of(t.begin(), t.end(), [&](VertexId v) { return d.vertices[v].z() == 0.0; })) continue;
    if (std::any_of(t.begin(), t.end(), [&](VertexId v) { return d.vertices[v].x() < 0.5; })) continue;
    d.required_edges.push_back(static_cast<std::uint32_t>(d.edges.size()));
    d.edges.push_back({t[0], t[1]});
    d.edge_refs.push_back(0);
    break;
  }
  for (VertexId v = 0; v < d.vertices.size(); ++v)
    if (d.vertices[v].y() == 1.0 && d.vertices[v].x() == 0.5 && d.vertices[v].z() == 0.5) {
      d.required_vertices.push_back(v);
      break;
    }
  return d;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("required edges and triangles: read and written in both encodings, their indices checked") {
    const io::MeshData d = box_with_required();
    REQUIRE(d.required_triangles.size() == 16);
    REQUIRE(d.required_edges.size() == 1);
    for (const char* name : {"required.mesh", "required.meshb"}) {
      CAPTURE(name);
      const TempDir dir;
      const std::string path = dir / name;
      io::write_meshb(path, d);
      const io::MeshData back = io::read_meshb(path);
      CHECK(back.required_edges == d.required_edges);
      CHECK(back.required_triangles == d.required_triangles);
      CHECK(back.required_vertices == d.required_vertices);
    }
    const TempDir dir;
    const std::string path = dir / "bad.mesh";
    io::MeshData bad = d;
    bad.required_triangles.push_back(static_cast<std::uint32_t>(d.triangles.size()));
    io::write_meshb(path, bad);
    try {
      io::read_meshb(path);
      FAIL("an out-of-range required triangle was read");
    } catch (const IoError& e) {
      CHECK(std::string(e.what()).find("RequiredTriangles") != std::string::npos);
    }
  }

  TEST_CASE("the keywords Mmg writes beside the mesh are read without harm: corners and ridges kept, normals skipped") {
    const TempDir dir;
    const std::string path = dir / "mmg.mesh";
    std::ofstream(path) << "MeshVersionFormatted 2\nDimension 3\n"
                           "Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                           "Edges 1\n1 2 3\n"
                           "Triangles 4\n2 3 4 1\n1 4 3 2\n1 2 4 3\n1 3 2 4\n"
                           "Tetrahedra 1\n1 2 3 4 1\n"
                           "Corners 1\n1\nRidges 1\n1\nRequiredVertices 1\n4\n"
                           "Normals 1\n0 0 1\nNormalAtVertices 1\n2 1\n"
                           "Tangents 1\n1 0 0\nTangentAtVertices 1\n2 1\nEnd\n";
    const io::MeshData d = io::read_meshb(path);
    CHECK(d.corners == std::vector<VertexId>{0});
    CHECK(d.ridges == std::vector<std::uint32_t>{0});
    const Mesh mesh = build_mesh(d);
    CHECK(mesh.validate().ok());
    CHECK(mesh.is_required(0));
    CHECK(mesh.is_required(3));
    CHECK(mesh.is_ridge(0, 1));
  }

  TEST_CASE("a required edge that is not an edge of the mesh is an input error") {
    io::MeshData d = box_with_required();
    // The two ends of a long diagonal of the box are never joined.
    VertexId lo = 0, hi = 0;
    for (VertexId v = 0; v < d.vertices.size(); ++v) {
      if (d.vertices[v] == Point(0, 0, 0)) lo = v;
      if (d.vertices[v] == Point(1, 1, 1)) hi = v;
    }
    d.required_edges.push_back(static_cast<std::uint32_t>(d.edges.size()));
    d.edges.push_back({lo, hi});
    d.edge_refs.push_back(0);
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("is not an edge of any tetrahedron"), InputError);
  }
}

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("required vertices, edges and triangles come out of an adaptation where they went in", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    const io::MeshData input = box_with_required();
    const Required before(input);
    for (const double h : {0.12, 0.5}) {
      CAPTURE(h);
      Mesh mesh = build_mesh(input);
      const MetricFunction metric = [h](const Point&) { return isotropic_metric(h); };
      set_metric_function(mesh, metric);
      AdaptOptions o;
      o.max_cycles = 4;
      adapt<S, typename T::Precision, typename T::Concurrency>(mesh, o, {.metric = &metric});
      require_valid(mesh, 1.0);
      const io::MeshData out = extract_mesh_data(mesh);
      const Required after(out);
      CHECK(after.triangles == before.triangles);
      // The required edges: those given, and those of the required triangles.
      std::set<Edge> edges = before.edges;
      for (const auto& t : before.triangles)
        for (int i = 0; i < 3; ++i) {
          Edge e{t[i], t[(i + 1) % 3]};
          std::sort(e.begin(), e.end());
          edges.insert(e);
        }
      CHECK(after.edges == edges);
      for (const auto& v : before.vertices) CHECK(after.vertices.count(v) == 1);
      // Every required triangle is still a surface triangle.
      const auto surface = surface_triangles(out);
      for (const auto& t : before.triangles) CHECK(surface.count(t) == 1);
      if (h < 0.25) CHECK(out.vertices.size() > 2 * input.vertices.size());
      static_cast<void>(S::name);
    }
  }

  TEST_CASE_TEMPLATE("with the surface kept, the volume is adapted and the surface comes out as it went in", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    const io::MeshData input = extract_mesh_data(make_box({.nx = 4, .ny = 4, .nz = 4}));
    for (const double h : {0.1, 0.5}) {
      CAPTURE(h);
      Mesh mesh = build_mesh(input);
      mesh.keep_surface();
      const MetricFunction metric = [h](const Point&) { return isotropic_metric(h); };
      set_metric_function(mesh, metric);
      AdaptOptions o;
      o.max_cycles = 4;
      shorten_when_slow<typename T::Precision>(o);
      adapt<S, typename T::Precision, typename T::Concurrency>(mesh, o, {.metric = &metric});
      require_valid(mesh, 1.0);
      const io::MeshData out = extract_mesh_data(mesh);
      CHECK(surface_triangles(out) == surface_triangles(input));
      if (h < 0.25) CHECK(out.vertices.size() > 2 * input.vertices.size());  // the volume refined
      static_cast<void>(S::name);
    }
  }
}
