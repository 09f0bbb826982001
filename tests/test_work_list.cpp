// Work lists in vertex order (operators/work_list.hpp): the law is that
// each gives what std::sort and std::unique give, on any input.
#include "test_support.hpp"

#include <metrica/operators/work_list.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <random>

using namespace metrica;

TEST_SUITE("property") {
  TEST_CASE("sort_unique_ids gives the sorted ids without repeats") {
    auto r = test::rng(31);
    for (std::size_t capacity : {1u, 7u, 1000u}) {
      std::uniform_int_distribution<std::uint32_t> id(0, static_cast<std::uint32_t>(capacity - 1));
      for (std::size_t n : {0u, 1u, 50u, 5000u}) {
        std::vector<std::uint32_t> ids(n);
        for (auto& x : ids) x = id(r);
        auto expected = ids;
        std::sort(expected.begin(), expected.end());
        expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
        sort_unique_ids(ids, capacity);
        CHECK(ids == expected);
      }
    }
  }

  TEST_CASE("sort_unique_by_vertex_key keeps one item per key in key order") {
    struct Item {
      std::uint64_t key;
      int order;  // the position in the input
    };
    auto r = test::rng(32);
    for (std::size_t capacity : {1u, 3u, 500u}) {
      std::uniform_int_distribution<std::uint32_t> vertex(0, static_cast<std::uint32_t>(capacity - 1));
      std::uniform_int_distribution<std::uint32_t> other(0, 40);
      for (std::size_t n : {0u, 1u, 60u, 20000u}) {
        std::vector<Item> items(n);
        for (std::size_t i = 0; i < n; ++i)
          items[i] = {(std::uint64_t{vertex(r)} << 32) | other(r), static_cast<int>(i)};
        auto expected = items;
        std::stable_sort(expected.begin(), expected.end(), [](const Item& x, const Item& y) { return x.key < y.key; });
        expected.erase(std::unique(expected.begin(), expected.end(),
                                   [](const Item& x, const Item& y) { return x.key == y.key; }),
                       expected.end());
        sort_unique_by_vertex_key(items, capacity, [](const Item& x) { return x.key; });
        REQUIRE(items.size() == expected.size());
        for (std::size_t i = 0; i < items.size(); ++i) CHECK(items[i].key == expected[i].key);
      }
    }
  }
}
