// Malformed libMeshb input: each case gives one clear IoError naming the
// file and the place, never a crash. Truncations at every byte and random
// corruptions (seeded) must either parse or throw IoError.
#include "test_support.hpp"

#include <metrica/error.hpp>
#include <metrica/io/meshb.hpp>

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>

using namespace metrica;
using namespace metrica::io;

namespace {

// The message of the IoError that parsing `bytes` raises ("" if none).
std::string error_of(const std::string& bytes, Encoding enc) {
  try {
    parse_mesh(bytes, enc, "bad");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string small_binary() { return read_file_bytes(test::ugawg("cube-linear-00.meshb")); }

void put32(std::string& bytes, std::size_t at, std::int32_t v) { std::memcpy(bytes.data() + at, &v, 4); }

const char* kTet = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("a missing file names the file") {
    try {
      read_meshb("/nonexistent/folder/none.meshb");
      FAIL("no error");
    } catch (const IoError& e) {
      CHECK(contains(e.what(), "/nonexistent/folder/none.meshb"));
      CHECK(contains(e.what(), "cannot open"));
    }
    CHECK_THROWS_AS(read_sol("/nonexistent.solb"), IoError);
    CHECK_THROWS_AS(read_meshb(test::ugawg("README.md")), IoError);  // unknown extension
  }

  TEST_CASE("binary: bad magic - version - dimension - offsets - counts - indices") {
    const auto good = small_binary();
    {
      auto b = good;
      put32(b, 0, 12345);
      CHECK(contains(error_of(b, Encoding::binary), "bad magic number"));
    }
    {
      auto b = good;
      put32(b, 4, 7);
      CHECK(contains(error_of(b, Encoding::binary), "unsupported libMeshb version 7"));
    }
    {
      auto b = good;
      put32(b, 16, 2);  // Dimension's value
      CHECK(contains(error_of(b, Encoding::binary), "unsupported dimension 2"));
    }
    {
      auto b = good;
      put32(b, 24, 999999);  // Vertices' next-keyword offset
      const auto e = error_of(b, Encoding::binary);
      CHECK(contains(e, "outside the file"));
      CHECK(contains(e, "Vertices"));
    }
    {
      auto b = good;
      put32(b, 28, 1 << 30);  // Vertices' count
      const auto e = error_of(b, Encoding::binary);
      CHECK(contains(e, "count 1073741824 exceeds the file"));
      CHECK(contains(e, "byte offset 28"));
    }
    {
      auto b = good;
      put32(b, 28, -5);
      CHECK(contains(error_of(b, Encoding::binary), "negative count"));
    }
    {
      // First triangle's first vertex: after Vertices (20 + 12 + 64 * 28)
      // and the Triangles header (12 bytes).
      auto b = good;
      put32(b, 20 + 12 + 64 * 28 + 12, 65);
      const auto e = error_of(b, Encoding::binary);
      CHECK(contains(e, "Triangles"));
      CHECK(contains(e, "vertex index 65 out of range 1..64"));
    }
    {
      auto b = good;
      put32(b, 20 + 12 + 64 * 28 + 12, 0);
      CHECK(contains(error_of(b, Encoding::binary), "index 0 out of range"));
    }
  }

  TEST_CASE("binary: a count that disagrees with the data - an offset that skips a keyword - are errors") {
    const auto good = small_binary();
    constexpr std::size_t triangles = 20 + 12 + 64 * 28;  // Triangles' keyword code
    std::int32_t after_triangles = 0;                     // its next-keyword offset
    std::memcpy(&after_triangles, good.data() + triangles + 4, 4);
    {
      auto b = good;
      put32(b, triangles + 8, 1);  // 1 triangle where the file holds 108
      const auto e = error_of(b, Encoding::binary);
      CHECK(contains(e, "Triangles"));
      CHECK(contains(e, "its count disagrees with the data"));
    }
    {
      auto b = good;
      put32(b, 24, after_triangles);  // Vertices' offset skips Triangles
      const auto e = error_of(b, Encoding::binary);
      CHECK(contains(e, "Vertices"));
      CHECK(contains(e, "skips data"));
    }
  }

  TEST_CASE("a folder given as a file is named as such") {
    test::TempDir dir;
    std::filesystem::create_directory(dir / "d.meshb");
    CHECK_THROWS_WITH_AS(read_meshb(dir / "d.meshb"), doctest::Contains("is a folder"), IoError);
  }

  TEST_CASE("binary: truncation at every byte gives an error - never a crash") {
    test::QuietLog quiet;
    const auto good = small_binary();
    std::size_t errors = 0;
    for (std::size_t n = 0; n < good.size(); ++n) {
      if (!error_of(good.substr(0, n), Encoding::binary).empty()) ++errors;
    }
    CHECK(errors == good.size());
    CHECK(contains(error_of(good.substr(0, 100), Encoding::binary), "truncated"));
  }

  TEST_CASE("binary and ASCII: random corruption parses or throws IoError") {
    test::QuietLog quiet;
    auto r = test::rng(2);
    for (auto enc : {Encoding::binary, Encoding::ascii}) {
      const auto good =
          read_file_bytes(test::ugawg(enc == Encoding::binary ? "cube-cylinder.meshb" : "cube-linear-00.mesh"));
      std::uniform_int_distribution<std::size_t> pos(0, good.size() - 1);
      std::uniform_int_distribution<int> byte(0, 255);
      for (int trial = 0; trial < 300; ++trial) {
        auto b = good;
        for (int k = 0; k < 4; ++k) b[pos(r)] = static_cast<char>(byte(r));
        try {
          parse_mesh(b, enc, "corrupt");
        } catch (const IoError&) {
        }
      }
    }
  }

  TEST_CASE("ASCII: each error names the line and the keyword") {
    {
      const auto e = error_of(std::string(kTet) + "Tetrahedra\n1\n1 2 3 x 0\nEnd\n", Encoding::ascii);
      CHECK(contains(e, "bad:11:"));
      CHECK(contains(e, "found 'x'"));
      CHECK(contains(e, "Tetrahedra"));
    }
    CHECK(contains(error_of(std::string(kTet) + "Tetrahedra\n1\n1 2 3 5 0\nEnd\n", Encoding::ascii),
                   "vertex index 5 out of range 1..4"));
    CHECK(contains(error_of(std::string(kTet) + "Tetrahedra\n100000\n1 2 3 4 0\n", Encoding::ascii),
                   "count 100000 exceeds"));
    CHECK(contains(error_of(std::string(kTet) + "Tetrahedra\n2\n1 2 3 4 0\n" + std::string(40, ' '), Encoding::ascii),
                   "unexpected end of file"));
    CHECK(contains(error_of("MeshVersionFormatted 2\nDimension 2\n", Encoding::ascii), "unsupported dimension 2"));
    CHECK(
        contains(error_of("MeshVersionFormatted 9\nDimension 3\n", Encoding::ascii), "unsupported libMeshb version 9"));
    CHECK(contains(error_of("MeshVersionFormatted 2\nVertices 1\n0 0 0 0\nEnd\n", Encoding::ascii), "no Dimension"));
    CHECK(contains(error_of("MeshVersionFormatted 2\nDimension 3\nEnd\n", Encoding::ascii), "no Vertices"));
    CHECK(contains(error_of("12 13 14\n", Encoding::ascii), "expected a keyword"));
    CHECK(contains(error_of("", Encoding::ascii), "no Dimension"));
  }

  TEST_CASE("solutions: unknown type - wrong size - missing keyword") {
    CHECK_THROWS_WITH_AS(
        parse_sol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 7\n1\nEnd\n", Encoding::ascii, "s.sol"),
        doctest::Contains("unknown solution type 7"), IoError);
    CHECK_THROWS_WITH_AS(
        parse_sol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n3\n1 3\n1 2 3\nEnd\n", Encoding::ascii, "s.sol"),
        doctest::Contains("exceeds"), IoError);
    CHECK_THROWS_WITH_AS(parse_sol("MeshVersionFormatted 2\nDimension 3\nEnd\n", Encoding::ascii, "s.sol"),
                         doctest::Contains("no SolAtVertices"), IoError);
    const auto solb = read_file_bytes(test::ugawg("cube-linear-00.solb"));
    CHECK_THROWS_AS(parse_sol(solb.substr(0, solb.size() / 2), Encoding::binary, "half.solb"), IoError);
  }
}
