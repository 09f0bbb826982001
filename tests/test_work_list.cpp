// Work lists in id order (operators/work_list.hpp): the law is that they
// give what std::sort and std::unique give, on any input.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/operators/work_list.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>

using namespace metrica;

TEST_SUITE("property") {
  TEST_CASE("unique_edge_seeds gives each edge once, in key order, with the first tet holding it") {
    auto r = test::rng(32);
    for (std::size_t capacity : {4u, 9u, 200u}) {
      std::uniform_int_distribution<VertexId> vertex(0, static_cast<VertexId>(capacity - 1));
      for (std::size_t n : {0u, 1u, 30u, 3000u}) {
        // Random tets of four distinct vertices; a random subset as seeds.
        std::vector<TetVertices> tets(n + 5);
        for (auto& t : tets) {
          do {
            for (auto& v : t) v = vertex(r);
          } while (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] || t[2] == t[3]);
        }
        std::vector<TetId> seeds;
        for (std::size_t i = 0; i < n; ++i) seeds.push_back(static_cast<TetId>((i * 7) % tets.size()));
        std::vector<std::pair<std::uint64_t, std::size_t>> all;  // key, position in seeds
        for (std::size_t i = 0; i < seeds.size(); ++i)
          for (const auto& e : kEdgeVertex) all.push_back({edge_key(tets[seeds[i]][e[0]], tets[seeds[i]][e[1]]), i});
        std::stable_sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        std::vector<EdgeSeed> expected;
        for (std::size_t i = 0; i < all.size(); ++i)
          if (i == 0 || all[i].first != all[i - 1].first) expected.push_back({all[i].first, seeds[all[i].second]});
        std::vector<EdgeSeed> got{{1, 2}};  // replaced, not appended to
        unique_edge_seeds(
            std::span<const TetId>(seeds), [&](TetId t) -> const TetVertices& { return tets[t]; }, capacity, got);
        REQUIRE(got.size() == expected.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
          CHECK(got[i].key() == expected[i].key());
          CHECK(got[i].tet == expected[i].tet);
        }
      }
    }
  }

  TEST_CASE("a mesh's unique edges in ranges of lower ends: the sorted distinct edges, in any number of ranges") {
    Mesh mesh = make_box({.nx = 4, .ny = 3, .nz = 5});
    // Some tets dead, so the buckets skip them.
    for (TetId t = 0; t < mesh.tet_capacity(); t += 7) mesh.remove_tet(t);
    std::set<std::pair<VertexId, VertexId>> expected;
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t))
        for (const auto& e : kEdgeVertex) {
          const VertexId a = mesh.tet(t)[e[0]], b = mesh.tet(t)[e[1]];
          expected.insert({std::min(a, b), std::max(a, b)});
        }
    const std::vector<std::pair<VertexId, VertexId>> sorted(expected.begin(), expected.end());
    for (std::size_t ranges : {0u, 1u, 2u, 3u, 8u, 1000u}) {
      CAPTURE(ranges);
      std::vector<std::pair<VertexId, VertexId>> got;
      for_each_unique_edge(
          mesh,
          [&](VertexId a, VertexId b) {
            got.push_back({a, b});
          },
          {}, ranges);
      CHECK(got == sorted);
    }
    // The tets counted and the buckets filled in parts, run in order and
    // in reverse: each edge once, whatever the parts.
    for (std::size_t parts : {2u, 3u, 8u, 11u}) {
      for (const bool reversed : {false, true}) {
        CAPTURE(parts);
        CAPTURE(reversed);
        const PartRunner run = reversed ? test::reversed_parts(parts) : PartRunner{parts, nullptr};
        std::vector<std::pair<VertexId, VertexId>> got;
        for_each_unique_edge(
            mesh, [&](VertexId a, VertexId b) { got.push_back({a, b}); }, run, 3);
        std::sort(got.begin(), got.end());
        CHECK(got == sorted);
      }
    }
    CHECK(unique_edge_ranges(0) == 1);
    CHECK(unique_edge_ranges(std::size_t{1} << 20) == 1);  // 4 MiB of entries
    CHECK(unique_edge_ranges((std::size_t{1} << 20) + 1) == 2);
    CHECK(unique_edge_ranges(std::size_t{3} << 20) == 3);
    CHECK(unique_edge_ranges(std::size_t{1} << 40) == 8);
  }
}
