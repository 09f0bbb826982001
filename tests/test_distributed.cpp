// The distributed executor's pieces that need no MPI: the vertex index,
// face keys and their orientation, the rendezvous ranks, the tets across
// each face within a part (distributed/neighbours.hpp), the tets a part
// keeps out of a round where its boundary is pinched
// (distributed/pinches.hpp). The executor itself runs under mpirun in
// tests/test_mpi.sh.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/distributed/neighbours.hpp>
#include <metrica/distributed/part.hpp>
#include <metrica/distributed/pinches.hpp>
#include <metrica/error.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

using namespace metrica;
using namespace metrica::distributed;

namespace {

// The part made of the box's tets whose centroid `keep` accepts: global
// ids are the box's vertex indices; a face of one kept tet that is not on
// the box's boundary is shared with rank 1.
Part part_of_box(const BoxSpec& spec, const std::function<bool(const Point&)>& keep) {
  const auto data = box_mesh_data(spec);
  Part part;
  for (std::size_t v = 0; v < data.vertices.size(); ++v) {
    part.vertex_ids.push_back(GlobalId(v));
    part.points.push_back(data.vertices[v]);
  }
  std::map<FaceKey, int> count;
  for (std::size_t t = 0; t < data.tets.size(); ++t) {
    const auto& v = data.tets[t];
    Point c = Point::Zero();
    for (auto i : v) c += data.vertices[i] / 4.0;
    if (!keep(c)) continue;
    part.tets.push_back({v[0], v[1], v[2], v[3]});
    part.tet_refs.push_back(1);
    for (const auto& f : kTetFaces) ++count[face_key(v[f[0]], v[f[1]], v[f[2]])];
  }
  auto on_box = [&](const FaceKey& k) {
    for (int c = 0; c < 3; ++c) {
      const double x = data.vertices[std::size_t(k[0])][c];
      if ((x == spec.lo[c] || x == spec.hi[c]) && data.vertices[std::size_t(k[1])][c] == x &&
          data.vertices[std::size_t(k[2])][c] == x)
        return true;
    }
    return false;
  };
  for (const auto& [k, n] : count)
    if (n == 1 && !on_box(k)) part.shared_faces.push_back(k), part.shared_with.push_back(1);
  return part;
}

}  // namespace

TEST_SUITE("property") {
  TEST_CASE("a vertex index finds each held id's first place and nothing else") {
    std::mt19937_64 rng(7);
    std::vector<GlobalId> ids;
    std::map<GlobalId, std::int64_t> first;
    for (int i = 0; i < 5000; ++i) {
      // Sparse, clustered and repeated ids, and the absent marker -1.
      const GlobalId g = i % 97 == 0 ? -1 : i % 5 == 0 ? GlobalId(rng() % 2000) : GlobalId(rng() >> 20);
      if (g >= 0) first.emplace(g, std::int64_t(ids.size()));
      ids.push_back(g);
    }
    const VertexIndex index(ids);
    for (const auto& [g, place] : first) CHECK(index.find(g) == place);
    CHECK(index.find(-1) == -1);
    for (int i = 0; i < 5000; ++i) {
      const auto g = GlobalId(rng() >> 20);
      CHECK(index.find(g) == (first.count(g) ? first[g] : -1));
    }
    const VertexIndex empty(std::vector<GlobalId>{});
    CHECK(empty.find(0) == -1);
  }

  TEST_CASE("a face key is sorted and oriented() turns it back into its triangle up to rotation") {
    auto r = test::rng(48);
    std::uniform_int_distribution<GlobalId> id(0, 1'000'000'000'000LL);
    for (int i = 0; i < 1000; ++i) {
      std::array<GlobalId, 3> t{id(r), id(r), id(r)};
      if (t[0] == t[1] || t[0] == t[2] || t[1] == t[2]) continue;
      const FaceKey k = face_key(t);
      CHECK(k[0] < k[1]);
      CHECK(k[1] < k[2]);
      const auto back = oriented(k, turned_over(t));
      const bool rotation = back == t || back == std::array<GlobalId, 3>{t[1], t[2], t[0]} ||
                            back == std::array<GlobalId, 3>{t[2], t[0], t[1]};
      CHECK(rotation);
    }
  }

  TEST_CASE("keeping a part's tets and the vertices they use leaves each tet its global ids and points") {
    const BoxSpec spec{3, 3, 3, Point(0, 0, 0), Point(3, 3, 3)};
    for (const bool shuffled : {false, true}) {
      CAPTURE(shuffled);
      Part part = part_of_box(spec, [](const Point&) { return true; });
      if (shuffled) {  // global ids unlike the local order
        auto r = test::rng(50);
        std::shuffle(part.vertex_ids.begin(), part.vertex_ids.end(), r);
      }
      auto r = test::rng(51);
      std::vector<bool> stays(part.tets.size());
      for (std::size_t t = 0; t < stays.size(); ++t) {  // the tets of one side, less some
        const auto& l = part.tets[t];
        const double x = (part.points[l[0]] + part.points[l[1]] + part.points[l[2]] + part.points[l[3]]).x() / 4;
        stays[t] = x < 1.6 && r() % 3 != 0;
      }
      std::vector<std::array<GlobalId, 4>> ids;
      std::vector<std::array<Point, 4>> points;
      for (std::size_t t = 0; t < stays.size(); ++t)
        if (stays[t]) {
          ids.push_back(global_tet(part, t));
          const auto& l = part.tets[t];
          points.push_back({part.points[l[0]], part.points[l[1]], part.points[l[2]], part.points[l[3]]});
        }
      keep_tets(part, stays);
      std::vector<bool> used(part.vertex_ids.size(), false);
      for (const auto& t : part.tets)
        for (auto v : t) used[v] = true;
      const auto kept = std::size_t(std::count(used.begin(), used.end(), true));
      REQUIRE(kept < used.size());  // some vertices go
      keep_vertices(part, used);
      REQUIRE(part.vertex_ids.size() == kept);
      REQUIRE(part.points.size() == kept);
      REQUIRE(part.tets.size() == ids.size());
      for (std::size_t t = 0; t < part.tets.size(); ++t) {
        CHECK(global_tet(part, t) == ids[t]);
        for (int c = 0; c < 4; ++c) CHECK(part.points[part.tets[t][std::size_t(c)]] == points[t][std::size_t(c)]);
        for (int f = 0; f < 4; ++f) {
          const auto& k = kTetFaces[f];
          CHECK(global_face(part, t, f) ==
                face_key(ids[t][std::size_t(k[0])], ids[t][std::size_t(k[1])], ids[t][std::size_t(k[2])]));
        }
      }
    }
  }

  TEST_CASE("the rendezvous rank of a face is the same for any order of its vertices and in range") {
    auto r = test::rng(49);
    std::uniform_int_distribution<GlobalId> id(0, 1'000'000);
    std::vector<int> hits(7, 0);
    for (int i = 0; i < 7000; ++i) {
      const GlobalId a = id(r), b = id(r), c = id(r);
      const int o = owner_of(face_key(a, b, c), 7);
      CHECK(o == owner_of(face_key(c, a, b), 7));
      REQUIRE(o >= 0);
      REQUIRE(o < 7);
      ++hits[std::size_t(o)];
    }
    for (int h : hits) CHECK(h > 700);  // spread: 1000 each on average
  }
}

TEST_SUITE("unit") {
  TEST_CASE("within a part, the tets across each face pair up both ways; the faces without one are its surface") {
    const BoxSpec spec{4, 3, 3, Point(0, 0, 0), Point(4, 3, 3)};
    // The part's vertices in the order of their global ids, then in
    // another (faces are paired at their lowest vertex in the part's own
    // numbering).
    for (const bool shuffled : {false, true}) {
      CAPTURE(shuffled);
      Part part = part_of_box(spec, [](const Point& c) { return c.x() + 0.5 * c.y() < 2.6; });
      if (shuffled) {
        std::vector<std::uint32_t> to(part.vertex_ids.size());
        std::iota(to.begin(), to.end(), 0u);
        std::shuffle(to.begin(), to.end(), std::mt19937_64(3));
        std::vector<GlobalId> ids(to.size());
        std::vector<Point> points(to.size());
        for (std::size_t v = 0; v < to.size(); ++v) ids[to[v]] = part.vertex_ids[v], points[to[v]] = part.points[v];
        part.vertex_ids = ids;
        part.points = points;
        for (auto& t : part.tets)
          for (auto& v : t) v = to[v];
      }
      const auto nb = local_neighbours(part);
      REQUIRE(nb.across.size() == part.tets.size());
      auto key = [&](std::size_t t, int f) { return global_face(part, t, f); };
      std::map<FaceKey, int> count;
      for (std::size_t t = 0; t < part.tets.size(); ++t)
        for (int f = 0; f < 4; ++f) ++count[key(t, f)];
      std::size_t paired = 0;
      for (std::size_t t = 0; t < part.tets.size(); ++t)
        for (int f = 0; f < 4; ++f) {
          const auto u = nb.across[t][std::size_t(f)];
          if (u < 0) continue;
          ++paired;
          CHECK(count[key(t, f)] == 2);
          int back = 0;
          for (int g = 0; g < 4; ++g)
            back += nb.across[std::size_t(u)][std::size_t(g)] == std::int32_t(t) && key(std::size_t(u), g) == key(t, f);
          CHECK(back == 1);
        }
      std::size_t single = 0;
      for (const auto& [k, n] : count) single += n == 1;
      CHECK(nb.open.size() == single);
      CHECK(paired + nb.open.size() == 4 * part.tets.size());
      CHECK(single > part.shared_faces.size());  // the box's faces and those shared
    }
  }

  TEST_CASE("a face of three tets in one part is an input error") {
    Part part;
    for (int v = 0; v < 6; ++v) {
      part.vertex_ids.push_back(10 * v);
      part.points.emplace_back(v, v * v, 1.0);
    }
    part.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}};
    part.tet_refs = {1, 1, 1};
    CHECK_THROWS_AS(local_neighbours(part), InputError);
  }

  TEST_CASE("a part without pinches is adapted whole") {
    const BoxSpec spec{4, 4, 4, Point(0, 0, 0), Point(4, 4, 4)};
    const Part part = part_of_box(spec, [](const Point& c) { return c.x() < 2; });
    REQUIRE(!part.shared_faces.empty());
    const auto active = adaptable_tets(part);
    CHECK(std::count(active.begin(), active.end(), true) == std::ptrdiff_t(part.tets.size()));
  }

  TEST_CASE("two blocks of a part touching at one vertex: the tets around it wait - the rest is a valid mesh") {
    const BoxSpec spec{4, 4, 4, Point(0, 0, 0), Point(4, 4, 4)};
    const Part part = part_of_box(spec, [](const Point& c) {
      return (c.x() < 2 && c.y() < 2 && c.z() < 2) || (c.x() > 2 && c.y() > 2 && c.z() > 2);
    });
    REQUIRE(part.tets.size() == 96);
    const auto active = adaptable_tets(part);
    const Point pinch(2, 2, 2);
    std::size_t out = 0;
    io::MeshData data;
    data.vertices = part.points;
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      bool at_pinch = false;
      for (auto v : part.tets[t]) at_pinch |= part.points[v] == pinch;
      CHECK(active[t] == !at_pinch);
      if (!active[t]) {
        ++out;
        continue;
      }
      const auto& v = part.tets[t];
      data.tets.push_back({VertexId(v[0]), VertexId(v[1]), VertexId(v[2]), VertexId(v[3])});
    }
    CHECK(out == 12);  // the two cells at the pinch, 6 tets each
    // What is left builds into a Mesh that passes every check.
    Mesh mesh = build_mesh(data);
    CHECK(mesh.validate().ok());
  }
}
