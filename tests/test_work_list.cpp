// Work lists in id order (operators/work_list.hpp): the law is that they
// give what std::sort and std::unique give, on any input.
#include "test_support.hpp"

#include <metrica/operators/work_list.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <random>

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
        unique_edge_seeds(std::span<const TetId>(seeds), [&](TetId t) -> const TetVertices& { return tets[t]; },
                          capacity, got);
        REQUIRE(got.size() == expected.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
          CHECK(got[i].key == expected[i].key);
          CHECK(got[i].tet == expected[i].tet);
        }
      }
    }
  }
}
