// Regions and internal surfaces: a box of two regions (x < 0.5: region 2,
// x > 0.5: region 3) whose interface x = 0.5 is given as triangles of
// surface id 10.
//   - built: the interface faces carry id 10 on both sides, their vertices
//     are marked, validate() checks both sides and the regions' faces;
//   - faces between regions with no triangle get the default id;
//   - adapted (refined and coarsened, on the interface too) under every
//     policy: the mesh stays valid, every vertex on the interface stays on
//     x = 0.5, each region
//     keeps its volume, the interface keeps its area and is written as
//     triangles of id 10;
//   - the interface's 2-2 flips, both sides together: on an interface whose
//     inner vertices were moved within it, they lift the worst tet and keep
//     the surface, its area and the regions exactly.
#include "operator_test_support.hpp"

#include <metrica/error.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>
#include <metrica/operators/interface_flip.hpp>
#include <metrica/pipeline/adapt.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace metrica;
using namespace metrica::test;

namespace {

constexpr SurfaceId kInterface = 10;

// The box's file content with regions by side and, when `triangles`, the
// interface's triangles.
io::MeshData two_region_box(int n, bool triangles) {
  io::MeshData d = extract_mesh_data(make_box({.nx = n, .ny = n, .nz = n}));
  d.tet_refs.assign(d.tets.size(), 0);
  for (std::size_t t = 0; t < d.tets.size(); ++t) {
    double x = 0.0;
    for (VertexId v : d.tets[t]) x += d.vertices[v].x() / 4.0;
    d.tet_refs[t] = x < 0.5 ? 2 : 3;
  }
  if (!triangles) return d;
  // The faces of region-2 tets whose three vertices lie on x = 0.5.
  for (std::size_t t = 0; t < d.tets.size(); ++t) {
    if (d.tet_refs[t] != 2) continue;
    for (int f = 0; f < 4; ++f) {
      const auto tri = face_vertices(d.tets[t], f);
      if (d.vertices[tri[0]].x() == 0.5 && d.vertices[tri[1]].x() == 0.5 && d.vertices[tri[2]].x() == 0.5) {
        d.triangles.push_back(tri);
        d.triangle_refs.push_back(kInterface);
      }
    }
  }
  return d;
}

double interface_area(const Mesh& mesh) { return surface_areas(mesh)[kInterface]; }

}  // namespace

TEST_SUITE("invariant") {
  TEST_CASE("internal surfaces: the interface's triangles become two-sided surface faces, checked by validate") {
    Mesh mesh = build_mesh(two_region_box(4, true));
    require_valid(mesh, 1.0);
    REQUIRE(mesh.has_internal_surfaces());
    std::size_t sides = 0;
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      for (int f = 0; f < 4; ++f) {
        if (mesh.internal_surface_id(t, f) == 0) continue;
        ++sides;
        CHECK(mesh.internal_surface_id(t, f) == kInterface);
        CHECK(mesh.internal_surface_id(mesh.neighbour(t, f).tet(), mesh.neighbour(t, f).face()) == kInterface);
        CHECK(mesh.tet_ref(t) != mesh.tet_ref(mesh.neighbour(t, f).tet()));
      }
    CHECK(sides == 2 * 2 * 16);  // 16 squares of two triangles, two sides each
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      CHECK(mesh.on_internal_surface(v) == (mesh.point(v).x() == 0.5));
    CHECK(interface_area(mesh) == doctest::Approx(1.0));
    const MeshSummary s = summarize(mesh);
    CHECK(s.internal_faces == 32);
    REQUIRE(s.regions.size() == 2);
    CHECK(s.regions.at(2).volume == doctest::Approx(0.5));
    CHECK(s.surfaces.at(kInterface).internal);
    // Written back: the interface's 32 triangles once each, with their id.
    const io::MeshData out = extract_mesh_data(mesh);
    CHECK(std::count(out.triangle_refs.begin(), out.triangle_refs.end(), kInterface) == 32);
    // One side's id changed: validate names the face.
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      for (int f = 0; f < 4; ++f)
        if (mesh.internal_surface_id(t, f) != 0) {
          mesh.set_internal_surface_id(t, f, kInterface + 1);
          const auto report = mesh.validate();
          CHECK_FALSE(report.ok());
          CHECK(report.to_string().find("internal surface") != std::string::npos);
          return;
        }
  }

  TEST_CASE("internal surfaces: contradictions are errors - an outer surface's id inside, a non-manifold surface") {
    // An interface triangle with the id of an outer boundary triangle.
    io::MeshData d = two_region_box(4, true);
    const auto inside = std::find(d.triangle_refs.begin(), d.triangle_refs.end(), kInterface);
    REQUIRE(inside != d.triangle_refs.end());
    *inside = d.triangle_refs.front();
    CHECK_THROWS_WITH_AS(build_mesh(d), doctest::Contains("an internal surface needs ids of its own"), InputError);
    // The planes x = 0.5 and y = 0.5 as one surface: the edges on their
    // common line lie on four of its faces.
    io::MeshData cross = two_region_box(4, true);
    for (std::size_t t = 0; t < cross.tets.size(); ++t) {
      double y = 0.0;
      for (VertexId v : cross.tets[t]) y += cross.vertices[v].y() / 4.0;
      if (y > 0.5) continue;
      for (int f = 0; f < 4; ++f) {
        const auto tri = face_vertices(cross.tets[t], f);
        if (std::all_of(tri.begin(), tri.end(), [&](VertexId v) { return cross.vertices[v].y() == 0.5; })) {
          cross.triangles.push_back(tri);
          cross.triangle_refs.push_back(kInterface);
        }
      }
    }
    const Mesh mesh = build_mesh(cross);
    const auto report = mesh.validate();
    CHECK_FALSE(report.ok());
    CHECK(report.to_string().find("faces of internal surface 10 (non-manifold)") != std::string::npos);
  }

  TEST_CASE("internal surfaces: faces between two regions with no triangle get the default surface id") {
    const Mesh mesh = build_mesh(two_region_box(4, false));
    require_valid(mesh, 1.0);
    SurfaceId largest = 0;
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      for (int f = 0; f < 4; ++f) largest = std::max(largest, mesh.surface_id(t, f));
    const MeshSummary s = summarize(mesh);
    CHECK(s.internal_faces == 2 * 16);
    CHECK(s.surfaces.at(largest + 1).internal);
  }

  TEST_CASE_TEMPLATE("internal surfaces: refined and coarsened, the interface stays where it is with its id", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    for (const double h : {0.12, 0.5}) {
      CAPTURE(h);
      Mesh mesh = build_mesh(two_region_box(4, true));
      const MetricFunction metric = [h](const Point&) { return isotropic_metric(h); };
      set_metric_function(mesh, metric);
      AdaptOptions o;
      o.max_cycles = 4;
      adapt<S, typename T::Precision, typename T::Concurrency>(mesh, o, {.metric = &metric});
      require_valid(mesh, 1.0);
      std::size_t on_interface = 0;
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
        if (!mesh.vertex_alive(v) || !mesh.on_internal_surface(v)) continue;
        ++on_interface;
        CHECK(mesh.point(v).x() == 0.5);
      }
      // Refined and coarsened on the interface too (25 vertices in the
      // input, 9 of them off the outer boundary).
      if (h < 0.25) CHECK(on_interface > 25);
      if (h > 0.25) CHECK(on_interface < 25);
      const MeshSummary s = summarize(mesh);
      REQUIRE(s.regions.size() == 2);
      CHECK(std::abs(s.regions.at(2).volume - 0.5) < 1e-12);
      CHECK(std::abs(s.regions.at(3).volume - 0.5) < 1e-12);
      CHECK(std::abs(interface_area(mesh) - 1.0) < 1e-12);
      const io::MeshData out = extract_mesh_data(mesh);
      double written = 0.0;
      for (std::size_t i = 0; i < out.triangles.size(); ++i)
        if (out.triangle_refs[i] == kInterface) {
          const auto& tri = out.triangles[i];
          written += triangle_area(out.vertices[tri[0]], out.vertices[tri[1]], out.vertices[tri[2]]);
        }
      CHECK(std::abs(written - 1.0) < 1e-12);
      static_cast<void>(S::name);
    }
  }

  TEST_CASE_TEMPLATE("internal surfaces: the 2-2 flips of the interface lift its tets and keep it", T,
                     METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using S = typename T::Space;
    using C = typename T::Concurrency;
    Mesh mesh = build_mesh(two_region_box(4, true));
    set_uniform_metric(mesh, 0.25);
    // The interface's inner vertices slide within x = 0.5: its triangles
    // and the tets on them get skewed; the interface stays where it was.
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      Point& p = mesh.point(v);
      if (p.x() != 0.5 || std::min({p.y(), p.z(), 1.0 - p.y(), 1.0 - p.z()}) < 0.1) continue;
      p.y() += 0.09 * (p.z() - 0.5) / 0.25;
      p.z() += 0.07;
    }
    require_valid(mesh, 1.0);
    const double before = worst_quality<S>(mesh);
    const OperatorStats stats = flip_interfaces<S, C>(mesh, {}, ModelOrFacets{});
    require_valid(mesh, 1.0);
    CHECK(stats.applied > 0);
    CHECK(worst_quality<S>(mesh) >= before);
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
      if (mesh.vertex_alive(v) && mesh.on_internal_surface(v)) CHECK(mesh.point(v).x() == 0.5);
    const MeshSummary s = summarize(mesh);
    CHECK(std::abs(s.regions.at(2).volume - 0.5) < 1e-12);
    CHECK(std::abs(s.regions.at(3).volume - 0.5) < 1e-12);
    CHECK(std::abs(interface_area(mesh) - 1.0) < 1e-12);
    CHECK(s.internal_faces == 32);  // flips keep the count of faces
  }
}
