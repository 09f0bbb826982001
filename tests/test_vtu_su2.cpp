// The .vtu and .su2 writers.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/io/vtu.hpp>

#include <doctest/doctest.h>

using namespace metrica;
using namespace metrica::io;

TEST_SUITE("unit") {
  TEST_CASE("base64 of the RFC 4648 test vectors") {
    auto b64 = [](const std::string& s) { return base64(s.data(), s.size()); };
    CHECK(b64("") == "");
    CHECK(b64("f") == "Zg==");
    CHECK(b64("fo") == "Zm8=");
    CHECK(b64("foo") == "Zm9v");
    CHECK(b64("foob") == "Zm9vYg==");
    CHECK(b64("fooba") == "Zm9vYmE=");
    CHECK(b64("foobar") == "Zm9vYmFy");
  }

  TEST_CASE("vtu: counts - fields - and a wrong field size is an error") {
    const auto d = box_mesh_data({.nx = 1, .ny = 1, .nz = 1});
    VtuField q{"quality", 1, std::vector<double>(d.tets.size(), 0.5)};
    VtuField m{"metric", 6, std::vector<double>(6 * d.vertices.size(), 1.0)};
    const auto xml = format_vtu(d, {m}, {q});
    CHECK(xml.find("NumberOfPoints=\"8\" NumberOfCells=\"6\"") != std::string::npos);
    CHECK(xml.find("Name=\"quality\"") != std::string::npos);
    CHECK(xml.find("Name=\"metric\" NumberOfComponents=\"6\"") != std::string::npos);
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
