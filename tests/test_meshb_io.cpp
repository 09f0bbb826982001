// libMeshb reading and writing: the real UGAWG files, round trips over
// every version and encoding, both byte orders, unknown keywords.
#include "test_support.hpp"

#include <metrica/io/meshb.hpp>

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

using namespace metrica;
using namespace metrica::io;

namespace {

// Rounds reals to float, as a version-1 file stores them. Through a
// volatile: GCC 12 -O2 folds the double->float->double round trip of this
// loop away when it vectorises it.
double to_float(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

MeshData as_float(MeshData m) {
  for (auto& p : m.vertices)
    for (int c = 0; c < 3; ++c) p[c] = to_float(p[c]);
  for (auto& list : m.on_geometry)
    for (auto& r : list) {
      r.u = to_float(r.u);
      r.v = to_float(r.v);
      r.dist = to_float(r.dist);
    }
  return m;
}

}  // namespace

TEST_SUITE("regression") {
  TEST_CASE("UGAWG files: counts of cube-linear-00 - cube-cylinder - cone-cone") {
    for (const char* name : {"cube-linear-00.mesh", "cube-linear-00.meshb"}) {
      const auto m = read_meshb(test::ugawg(name));
      CHECK(m.vertices.size() == 64);
      CHECK(m.triangles.size() == 108);
      CHECK(m.tets.size() == 162);
      CHECK(m.version == 2);
    }
    for (const char* name : {"cube-cylinder.mesh", "cube-cylinder.meshb"}) {
      const auto m = read_meshb(test::ugawg(name));
      CHECK(m.vertices.size() == 286);
      CHECK(m.triangles.size() == 418);
      CHECK(m.tets.size() == 952);
    }
    const auto cc = read_meshb(test::ugawg("cone-cone.meshb"));
    CHECK(cc.vertices.size() == 17);
    CHECK(cc.triangles.size() == 28);
    CHECK(cc.tets.size() == 23);
  }

  TEST_CASE("ASCII and binary UGAWG files hold the same mesh") {
    for (const char* base : {"cube-linear-00", "cube-cylinder"}) {
      const auto a = read_meshb(test::ugawg(std::string(base) + ".mesh"));
      const auto b = read_meshb(test::ugawg(std::string(base) + ".meshb"));
      CHECK(a.tets == b.tets);
      CHECK(a.triangles == b.triangles);
      CHECK(a.triangle_refs == b.triangle_refs);
      REQUIRE(a.vertices.size() == b.vertices.size());
      // The ASCII files print 13-15 significant digits, and the two
      // cube-cylinder files come from different writers.
      for (std::size_t i = 0; i < a.vertices.size(); ++i) CHECK((a.vertices[i] - b.vertices[i]).norm() < 1e-7);
    }
  }

  TEST_CASE("UGAWG solution: the linear metric on cube-linear-00") {
    const auto a = read_sol(test::ugawg("cube-linear-00.sol"));
    const auto b = read_sol(test::ugawg("cube-linear-00.solb"));
    CHECK(a.count == 64);
    REQUIRE(a.types == std::vector<SolType>{SolType::sym_matrix});
    CHECK(b.types == a.types);
    CHECK(b.count == a.count);
    for (std::size_t i = 0; i < a.values.size(); ++i) CHECK(a.values[i] == doctest::Approx(b.values[i]).epsilon(1e-14));
    // h = 0.1 in x and y: M_xx = M_yy = 100, no coupling.
    CHECK(b.values[0] == doctest::Approx(100.0));
    CHECK(b.values[1] == 0.0);
  }

  TEST_CASE("the cube-cylinder .meshb with CAD keywords and ByteFlow is read - the CAD skipped") {
    const auto m = read_meshb(test::ugawg("cube-cylinder.meshb"));
    CHECK(m.edges.size() == 62);
    CHECK(m.tets.size() == 952);
  }
}

TEST_SUITE("unit") {
  TEST_CASE("round trip read -> write -> read is identical for every version and encoding") {
    for (const char* name : {"cube-linear-00.meshb", "cube-cylinder.meshb", "cone-cone.meshb"}) {
      const auto original = read_meshb(test::ugawg(name));
      const std::string file = name;
      for (int version = 1; version <= 4; ++version) {
        for (auto enc : {Encoding::ascii, Encoding::binary}) {
          CAPTURE(file);
          CAPTURE(version);
          CAPTURE(enc == Encoding::binary);
          auto expected = version == 1 ? as_float(original) : original;
          expected.version = version;
          const auto once = parse_mesh(format_mesh(original, enc, version), enc, "once");
          CHECK(once == expected);
          // A second trip through the same version changes nothing.
          const auto twice = parse_mesh(format_mesh(once, enc), enc, "twice");
          CHECK(twice == once);
        }
      }
    }
  }

  TEST_CASE("binary files through the filesystem: written atomically - read back") {
    test::TempDir dir;
    const auto m = read_meshb(test::ugawg("cube-linear-00.mesh"));
    write_meshb(dir / "a.meshb", m);
    write_meshb(dir / "a.mesh", m, 4);
    CHECK(read_meshb(dir / "a.meshb") == m);
    auto v4 = m;
    v4.version = 4;
    CHECK(read_meshb(dir / "a.mesh") == v4);
    // No temporary file is left behind.
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
    CHECK(files == 2);
  }

  TEST_CASE("files beyond the writers' 1 MiB buffer: streamed in pieces - the same bytes as the whole output") {
    // 60k vertices and tets: several flushes inside each keyword, and the
    // next-keyword offsets of binary files patched in the file itself.
    MeshData m;
    m.version = 2;
    auto r = test::rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::uint32_t n = 60000;
    for (std::uint32_t i = 0; i < n; ++i) {
      m.vertices.push_back(test::draw_point(u, r));
      m.vertex_refs.push_back(static_cast<int>(i % 7));
      m.tets.push_back({i, (i + 1) % n, (i + 2) % n, (i + 3) % n});
      m.tet_refs.push_back(static_cast<int>(i % 3));
    }
    for (std::uint32_t i = 0; i < 1000; ++i) {
      m.triangles.push_back({i, i + 1, i + 2});
      m.triangle_refs.push_back(1 + static_cast<int>(i % 6));
    }
    m.corners = {0, 5, 17};
    SolData s;
    s.count = n;
    s.types = {SolType::sym_matrix};
    for (std::size_t i = 0; i < n * 6; ++i) s.values.push_back(u(r));
    test::TempDir dir;
    auto bytes_of = [](const std::string& path) {
      std::ifstream in(path, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (int version : {2, 3}) {
      CAPTURE(version);
      write_meshb(dir / "m.meshb", m, version);
      write_meshb(dir / "m.mesh", m, version);
      write_sol(dir / "s.solb", s, version);
      write_sol(dir / "s.sol", s, version);
      const std::string binary = bytes_of(dir / "m.meshb");
      REQUIRE(binary.size() > (std::size_t{2} << 20));
      CHECK(binary == format_mesh(m, Encoding::binary, version));
      CHECK(bytes_of(dir / "m.mesh") == format_mesh(m, Encoding::ascii, version));
      CHECK(bytes_of(dir / "s.solb") == format_sol(s, Encoding::binary, version));
      CHECK(bytes_of(dir / "s.sol") == format_sol(s, Encoding::ascii, version));
      auto expected = m;
      expected.version = version;
      CHECK(read_meshb(dir / "m.meshb") == expected);
    }
  }

  TEST_CASE("solutions with several fields round-trip in every version and encoding") {
    SolData s;
    s.count = 5;
    s.types = {SolType::scalar, SolType::vector, SolType::sym_matrix, SolType::matrix};
    CHECK(s.stride() == 19);
    CHECK(s.offset(2) == 4);
    auto r = test::rng(1);
    std::uniform_real_distribution<double> u(-1e3, 1e3);
    for (std::size_t i = 0; i < s.count * 19; ++i) s.values.push_back(u(r));
    for (int version = 2; version <= 4; ++version)
      for (auto enc : {Encoding::ascii, Encoding::binary}) {
        auto expected = s;
        expected.version = version;
        CHECK(parse_sol(format_sol(s, enc, version), enc, "sol") == expected);
      }
    const auto field = s.field(2);
    REQUIRE(field.size() == 30);
    CHECK(field[6] == s.values[19 + 4]);
  }

  TEST_CASE("big-endian binary files are read") {
    // A one-tet mesh written word by word in big-endian order (version 2).
    std::string bytes;
    auto word = [&](std::uint32_t w) {
      w = __builtin_bswap32(w);
      bytes.append(reinterpret_cast<const char*>(&w), 4);
    };
    auto real = [&](double x) {
      std::uint64_t u;
      std::memcpy(&u, &x, 8);
      u = __builtin_bswap64(u);
      bytes.append(reinterpret_cast<const char*>(&u), 8);
    };
    word(1);
    word(2);
    word(3);  // Dimension
    word(20);
    word(3);
    word(4);  // Vertices: 12 + 4 * 28 bytes
    word(20 + 12 + 4 * 28);
    word(4);
    const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& p : xyz) {
      for (double c : p) real(c);
      word(7);
    }
    const auto tets_at = static_cast<std::uint32_t>(bytes.size());
    word(8);  // Tetrahedra
    word(tets_at + 12 + 20);
    word(1);
    for (std::uint32_t v : {1u, 2u, 3u, 4u, 9u}) word(v);
    word(54);  // End
    word(0);
    const auto m = parse_mesh(bytes, Encoding::binary, "big-endian");
    REQUIRE(m.vertices.size() == 4);
    CHECK(m.vertices[1] == Point(1, 0, 0));
    CHECK(m.vertex_refs[3] == 7);
    REQUIRE(m.tets.size() == 1);
    CHECK(m.tets[0] == TetVertices{0, 1, 2, 3});
    CHECK(m.tet_refs[0] == 9);
  }

  TEST_CASE("ASCII: comments - unknown keywords and layout freedom") {
    const std::string text =
        "# written by hand\nMeshVersionFormatted 2\nDimension\n3\n"
        "Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
        "NormalAtVertices 1\n1 1\nNormals 1 0 0 1\n"  // unknown to Metrica: skipped
        "Tetrahedra\n1\n1 2 3 4 2  # trailing comment\nEnd\n";
    const auto m = parse_mesh(text, Encoding::ascii, "hand.mesh");
    CHECK(m.vertices.size() == 4);
    REQUIRE(m.tets.size() == 1);
    CHECK(m.tet_refs[0] == 2);
  }
}
