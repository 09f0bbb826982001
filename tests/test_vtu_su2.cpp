// The .vtu and .su2 writers.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/io/vtu.hpp>

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>

using namespace metrica;
using namespace metrica::io;

TEST_SUITE("unit") {
  TEST_CASE("vtu: counts - fields - and a wrong field size is an error") {
    const auto d = box_mesh_data({.nx = 1, .ny = 1, .nz = 1});
    VtuField q{"quality", 1, std::vector<double>(d.tets.size(), 0.5)};
    VtuField m{"metric", 6, std::vector<double>(6 * d.vertices.size(), 1.0)};
    const auto xml = format_vtu(d, {m}, {q});
    CHECK(xml.find("NumberOfPoints=\"8\" NumberOfCells=\"6\"") != std::string::npos);
    CHECK(xml.find("Name=\"quality\"") != std::string::npos);
    CHECK(xml.find("Name=\"metric\" NumberOfComponents=\"6\"") != std::string::npos);
    // The appended block as the layout places it: each array's count,
    // then its values (the metric's first entry, the quality of tet 6).
    const VtuLayout layout(8, 6, {{"metric", 6}}, {{"quality", 1}});
    CHECK(xml.compare(0, layout.head().size(), layout.head()) == 0);
    CHECK(xml.size() == layout.tail_at() + std::string(VtuLayout::tail()).size());
    std::uint64_t count = 0;
    double value = 0.0;
    std::memcpy(&count, xml.data() + layout.count_at(VtuLayout::kFirstPointField), 8);
    CHECK(count == 8 * 6 * 8);
    std::memcpy(&value, xml.data() + layout.values_at(VtuLayout::kFirstPointField), 8);
    CHECK(value == 1.0);
    std::memcpy(&value, xml.data() + layout.values_at(layout.refs() + 1) + 5 * 8, 8);
    CHECK(value == 0.5);
    std::int64_t last_offset = 0;
    std::memcpy(&last_offset, xml.data() + layout.values_at(VtuLayout::kOffsets) + 5 * 8, 8);
    CHECK(last_offset == 24);
    VtuField bad{"bad", 1, {1.0}};
    CHECK_THROWS_AS(format_vtu(d, {bad}, {}), InputError);
  }

  TEST_CASE("su2: elements - points and one marker per surface id") {
    const auto d = box_mesh_data({.nx = 1, .ny = 1, .nz = 1});
    const auto text = format_su2(d);
    CHECK(text.find("NELEM= 6\n") != std::string::npos);
    CHECK(text.find("NPOIN= 8\n") != std::string::npos);
    CHECK(text.find("NMARK= 6\n") != std::string::npos);
    CHECK(text.find("MARKER_TAG= 6\nMARKER_ELEMS= 2\n") != std::string::npos);
  }
}
