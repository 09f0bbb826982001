// Attributes of a mesh's vertices and tets (attributes.hpp):
//   - a column has a value for every id; made and reused entities take the
//     initial value, dead room too when asked; compaction carries values;
//   - a copy's columns are its own (the library's accessors read them);
//   - names are unique, a type is checked, the library's own stay;
//   - a user's columns survive an adaptation under every policy:
//     kept vertices keep their value, kept tets theirs, new ones the
//     initial value.
#include "operator_test_support.hpp"

#include <metrica/attributes.hpp>
#include <metrica/box.hpp>
#include <metrica/mesh.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

using namespace metrica;
using namespace metrica::test;

TEST_SUITE("invariant") {
  TEST_CASE("a column grows with the entities, made and reused ones take the initial value") {
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    const std::size_t nv = mesh.vertex_capacity(), nt = mesh.tet_capacity();
    auto& tag = mesh.add_vertex_attribute<std::int64_t>("tag", -1);
    auto& weight = mesh.add_tet_attribute<double>("weight", 0.5);
    REQUIRE(tag.size() == nv);
    REQUIRE(weight.size() == nt);
    for (VertexId v = 0; v < nv; ++v) tag[v] = v;
    for (TetId t = 0; t < nt; ++t) weight[t] = 2.0 * t;

    const VertexId fresh = mesh.add_vertex(Point(9, 9, 9));
    CHECK(tag.size() == nv + 1);
    CHECK(tag[fresh] == -1);
    mesh.remove_vertex(fresh);
    tag[fresh] = 42;
    CHECK(mesh.add_vertex(Point(8, 8, 8)) == fresh);  // the free list gives the id back
    CHECK(tag[fresh] == -1);
    mesh.remove_vertex(fresh);

    const TetId t0 = 0;
    const TetVertices vs = mesh.tet(t0);
    mesh.remove_tet(t0);
    CHECK(mesh.add_tet(vs) == t0);
    CHECK(weight[t0] == 0.5);
    CHECK(mesh.find_vertex_attribute<std::int64_t>("tag") == &tag);
    CHECK(mesh.find_tet_attribute<double>("none") == nullptr);
  }

  TEST_CASE("dead room: unwritten or the initial value; compaction carries every value to its entity") {
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    auto& tag = mesh.add_vertex_attribute<std::int64_t>("tag", -1);
    auto& sum = mesh.add_tet_attribute<std::int64_t>("sum", 0);
    mesh.enable_geo_params();
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) tag[v] = 1000 + v;
    const std::size_t nv = mesh.vertex_capacity();
    const DeadRoom room = mesh.add_dead_room(5, 7);
    CHECK(room.first_vertex == nv);
    CHECK(tag.size() == nv + 5);
    CHECK(mesh.find_vertex_attribute<GeoParam>(attribute_name::cad_parameters)->size() == nv + 5);
    CHECK(mesh.geo_param(VertexId(nv + 4)) == GeoParam{});  // DeadRoomFill::initial
    CHECK(sum.size() == mesh.tet_capacity());

    // Each vertex's tag names its original id; each tet's value is the sum
    // of its vertices' tags, which must hold after renumbering.
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t))
        for (VertexId v : mesh.tet(t)) sum[t] += tag[v];
    std::vector<Point> where(nv);
    for (VertexId v = 0; v < nv; ++v) where[v] = mesh.point(v);
    mesh.compact();
    REQUIRE(tag.size() == mesh.num_vertices());
    REQUIRE(sum.size() == mesh.num_tets());
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) CHECK(mesh.point(v) == where[std::size_t(tag[v] - 1000)]);
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      std::int64_t s = 0;
      for (VertexId v : mesh.tet(t)) s += tag[v];
      CHECK(sum[t] == s);
    }
  }

  TEST_CASE("a copy's columns are its own, and the library's accessors read the copy's") {
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    set_uniform_metric(mesh, 0.5);
    auto& tag = mesh.add_vertex_attribute<int>("tag", 7);
    Mesh copy = mesh;
    Sym6 other{};
    other[0] = other[2] = other[5] = 1.0;
    copy.set_metric(0, other, Sym6{});
    copy.find_vertex_attribute<int>("tag")->fill(3);
    copy.cache_quality(0, 0.25);
    CHECK(mesh.metric(0)[0] == doctest::Approx(4.0));
    CHECK(copy.metric(0)[0] == 1.0);
    CHECK(tag[0] == 7);
    CHECK(mesh.cached_quality(0) == Mesh::kUnknownQuality);
    CHECK(copy.cached_quality(0) == 0.25);

    Mesh moved = std::move(copy);
    CHECK(moved.metric(0)[0] == 1.0);
    CHECK((*moved.find_vertex_attribute<int>("tag"))[1] == 3);
    copy = mesh;  // a moved-from mesh takes a copy again
    CHECK(copy.metric(0)[0] == doctest::Approx(4.0));
  }

  TEST_CASE("names are unique, a column's type is checked, the library's own columns stay") {
    Mesh mesh = make_box({.nx = 1, .ny = 1, .nz = 1});
    set_uniform_metric(mesh, 0.5);
    mesh.add_vertex_attribute<int>("tag", 0);
    CHECK_THROWS_AS(mesh.add_vertex_attribute<int>("tag", 1), std::invalid_argument);
    CHECK_THROWS_AS(mesh.add_vertex_attribute<double>(std::string(attribute_name::metric), 0.0), std::invalid_argument);
    // Not there yet (no model), the library's name all the same.
    CHECK_THROWS_AS(mesh.add_vertex_attribute<GeoParam>(std::string(attribute_name::cad_parameters), GeoParam{}),
                    std::invalid_argument);
    CHECK_THROWS_AS(mesh.find_vertex_attribute<double>("tag"), std::invalid_argument);
    CHECK_THROWS_AS(mesh.remove_vertex_attribute(attribute_name::metric), std::invalid_argument);
    CHECK_THROWS_AS(mesh.remove_tet_attribute(attribute_name::mean_ratio_cache), std::invalid_argument);
    CHECK(mesh.remove_vertex_attribute("tag"));
    CHECK_FALSE(mesh.remove_vertex_attribute("tag"));
    CHECK(mesh.find_vertex_attribute<int>("tag") == nullptr);
    const auto names = mesh.vertex_attributes().names();
    CHECK(std::find(names.begin(), names.end(), "metric") != names.end());
  }

  TEST_CASE_TEMPLATE(
      "a user's columns survive an adaptation: kept entities keep their values, new ones "
      "take the initial value",
      T, METRICA_POLICY_COMBINATIONS) {
    const ExecutorOf<T> executor;
    using A = Adapter<typename T::Space, typename T::Concurrency>;
    Mesh mesh = small_linear_box();
    mesh.keep_surface();  // its vertices and faces stay: each must keep its tag
    const double volume = mesh.volume();
    auto& tag = mesh.add_vertex_attribute<std::int64_t>("tag", -1);
    auto& origin = mesh.add_tet_attribute<std::int64_t>("origin", -1);
    std::vector<Point> where;
    std::set<std::array<std::int64_t, 4>> tets_before;
    std::size_t surface = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      tag[v] = std::int64_t(v);
      where.push_back(mesh.point(v));
      surface += mesh.vertex_class(v) != VertexClass::interior;
    }
    auto tags_of = [&](TetId t) {
      std::array<std::int64_t, 4> k;
      for (int i = 0; i < 4; ++i) k[std::size_t(i)] = tag[mesh.tet(t)[std::size_t(i)]];
      std::sort(k.begin(), k.end());
      return k;
    };
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      origin[t] = std::int64_t(t);
      tets_before.insert(tags_of(t));
    }
    // The box's own sizes where x < 0.5 (its edges in the unit band: most
    // of its tets stay), the linear field's beyond.
    const MetricFunction metric = [](const Point& p) { return p.x() < 0.5 ? isotropic_metric(0.45) : small_linear(p); };
    set_metric_function(mesh, metric);
    A adapter(mesh, &metric);
    // A few cycles make every kind of change (splits, collapses, flips,
    // moves) many times over: enough, and short under the sanitizers.
    AdaptOptions o;
    o.max_cycles = 3;
    o.quality_passes = 1;
    o.repair_rounds = 0;
    const AdaptReport r = run_pipeline(adapter, standard_pipeline<A>(o));
    require_valid(mesh, volume);
    REQUIRE(r.ops.get("split").applied > 0);

    auto& tag_after = *mesh.find_vertex_attribute<std::int64_t>("tag");
    auto& origin_after = *mesh.find_tet_attribute<std::int64_t>("origin");
    std::set<std::int64_t> seen;
    std::size_t surface_tagged = 0, fresh = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
      if (!mesh.vertex_alive(v)) continue;
      const std::int64_t g = tag_after[v];
      if (g < 0) {
        ++fresh;
        continue;
      }
      CHECK(seen.insert(g).second);  // one vertex a tag
      if (mesh.vertex_class(v) != VertexClass::interior) {
        CHECK(mesh.point(v) == where[std::size_t(g)]);  // a kept surface vertex never moves
        ++surface_tagged;
      }
    }
    CHECK(surface_tagged == surface);
    CHECK(fresh > 0);
    std::size_t kept_tets = 0;
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      if (!mesh.tet_alive(t) || origin_after[t] < 0) continue;
      ++kept_tets;
      // A tet with its original value was never rewritten: its vertices
      // are the ones it had.
      std::array<std::int64_t, 4> k;
      for (int i = 0; i < 4; ++i) k[std::size_t(i)] = tag_after[mesh.tet(t)[std::size_t(i)]];
      std::sort(k.begin(), k.end());
      CHECK(tets_before.count(k) == 1);
    }
    CHECK(kept_tets > 0);
    CHECK(kept_tets < tets_before.size());
  }
}
