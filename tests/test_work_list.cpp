// Work lists in id order (operators/work_list.hpp): the law is that they
// give what std::sort and std::unique give, on any input.
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
}
