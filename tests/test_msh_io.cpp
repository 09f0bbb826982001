// gmsh's .msh: the same mesh written by gmsh in versions 4.1 and 2.2,
// ASCII and binary (tests/data/msh), read alike with its physical groups
// as regions and surface ids; written by us in both versions and read back
// to the bit; malformed files are clear errors.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/msh.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <cmath>
#include <numbers>
#include <string>

using namespace metrica;
using namespace metrica::io;

namespace {

std::string msh_file(const char* name) { return std::string(METRICA_TEST_DATA_DIR) + "/msh/" + name; }

constexpr const char* kFiles[] = {"box_sphere_41.msh", "box_sphere_41_binary.msh", "box_sphere_22.msh",
                                  "box_sphere_22_binary.msh"};

std::size_t count(const std::vector<int>& refs, int ref) {
  return static_cast<std::size_t>(std::count(refs.begin(), refs.end(), ref));
}

void check_throws_with(const std::string& text, const std::string& part) {
  try {
    parse_msh(text, "bad.msh");
    FAIL("no error for: " << part);
  } catch (const IoError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find(part) != std::string::npos);
  }
}

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("msh: gmsh's 4.1 and 2.2 files, ASCII and binary, read as the same mesh with its physical groups") {
    const MeshData first = read_msh(msh_file(kFiles[0]));
    REQUIRE(first.tets.size() > 500);
    // Regions: 2 outside the sphere, 3 inside; the sphere's triangles 100,
    // the cube's faces 8 to 13.
    CHECK(count(first.tet_refs, 2) + count(first.tet_refs, 3) == first.tets.size());
    CHECK(count(first.tet_refs, 3) > 0);
    const std::size_t sphere = count(first.triangle_refs, 100);
    CHECK(sphere > 50);
    for (int face = 8; face <= 13; ++face) CHECK(count(first.triangle_refs, face) > 0);
    for (const char* file : kFiles) {
      CAPTURE(file);
      const MeshData d = read_msh(msh_file(file));
      CHECK(d.vertices.size() == first.vertices.size());
      CHECK(d.tets == first.tets);
      CHECK(d.tet_refs == first.tet_refs);
      CHECK(d.triangles == first.triangles);
      CHECK(d.triangle_refs == first.triangle_refs);
      // gmsh writes ASCII coordinates to 16 digits, binary ones exactly.
      for (std::size_t v = 0; v < d.vertices.size(); ++v) REQUIRE((d.vertices[v] - first.vertices[v]).norm() < 1e-15);
    }
    // Built: the sphere is an internal surface between the two regions.
    BuildOptions bo;
    bo.source = kFiles[0];
    const Mesh mesh = build_mesh(first, bo);
    REQUIRE(mesh.validate().ok());
    const MeshSummary s = summarize(mesh);
    CHECK(s.internal_faces == sphere);
    CHECK(s.surfaces.at(100).internal);
    CHECK(s.volume == doctest::Approx(1.0).epsilon(1e-12));
    const double ball = 4.0 / 3.0 * std::numbers::pi * 0.3 * 0.3 * 0.3;
    CHECK(std::abs(s.regions.at(3).volume - ball) < 0.15 * ball);  // the sphere faceted at size 0.25
    CHECK(s.regions.at(2).volume + s.regions.at(3).volume == doctest::Approx(1.0));
  }

  TEST_CASE("msh: written in 4.1 and 2.2, ASCII and binary, and read back to the bit") {
    const MeshData d = read_msh(msh_file(kFiles[0]));
    // Elements with their refs, as sets: a 4.1 file groups them by entity.
    auto tets = [](const MeshData& m) {
      std::vector<std::pair<TetVertices, int>> out;
      for (std::size_t i = 0; i < m.tets.size(); ++i) out.emplace_back(m.tets[i], m.tet_refs[i]);
      std::sort(out.begin(), out.end());
      return out;
    };
    auto triangles = [](const MeshData& m) {
      std::vector<std::pair<TriangleVertices, int>> out;
      for (std::size_t i = 0; i < m.triangles.size(); ++i) out.emplace_back(m.triangles[i], m.triangle_refs[i]);
      std::sort(out.begin(), out.end());
      return out;
    };
    for (const MshVersion v : {MshVersion::v41, MshVersion::v22})
      for (const Encoding e : {Encoding::ascii, Encoding::binary}) {
        CAPTURE(e == Encoding::binary);
        const MeshData back = parse_msh(format_msh(d, v, e), "back.msh");
        CHECK(back.vertices == d.vertices);
        CHECK(tets(back) == tets(d));
        CHECK(triangles(back) == triangles(d));
      }
    CHECK(format_of("a.msh") == FileFormat::msh);
  }

  TEST_CASE("msh: region 0 beside other regions is a physical group of its own - read back as 0") {
    // The UGAWG cube's tets are region 0 and its faces surfaces 1 to 6: a
    // file with some entities in groups and others not is refused by
    // meshio and by our reader, so every entity gets its group.
    MeshData d = box_mesh_data({.nx = 2, .ny = 1, .nz = 1});
    for (std::size_t t = 0; t < d.tets.size(); ++t) d.tet_refs[t] = t < 6 ? 0 : 5;
    for (const Encoding e : {Encoding::ascii, Encoding::binary}) {
      const std::string text = format_msh(d, MshVersion::v41, e);
      const MeshData back = parse_msh(text, "back.msh");
      CHECK(back.tets.size() == d.tets.size());
      CHECK(std::count(back.tet_refs.begin(), back.tet_refs.end(), 0) == 6);
      CHECK(std::count(back.tet_refs.begin(), back.tet_refs.end(), 5) == 6);
      auto ids = back.triangle_refs;
      std::sort(ids.begin(), ids.end());
      auto expected = d.triangle_refs;
      std::sort(expected.begin(), expected.end());
      CHECK(ids == expected);
    }
    // Every ref 0: no groups at all.
    MeshData bare = d;
    std::fill(bare.tet_refs.begin(), bare.tet_refs.end(), 0);
    std::fill(bare.triangle_refs.begin(), bare.triangle_refs.end(), 0);
    const std::string text = format_msh(bare, MshVersion::v41, Encoding::ascii);
    const std::size_t at = text.find("$Entities\n0 0 1 1\n");
    REQUIRE(at != std::string::npos);
    std::istringstream lines(text.substr(at));
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    for (int entity = 0; entity < 2; ++entity) {
      std::getline(lines, line);
      CHECK(line.ends_with(" 0 0"));  // no physical tag, no bounding entity
    }
  }

  TEST_CASE("msh: other elements are dropped with a count - second-order tets keep their corners") {
    const std::string text =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n6 2 0 0\n"
        "7 2 1 0\n$EndNodes\n$Elements\n3\n1 4 2 7 7 1 2 3 4\n2 6 2 8 8 1 2 3 5 6 7\n3 15 2 9 9 5\n$EndElements\n";
    const MeshData d = parse_msh(text, "mixed.msh");
    CHECK(d.tets.size() == 1);
    CHECK(d.tet_refs == std::vector<int>{7});
    CHECK(d.corners.size() == 1);
    const std::string tet10 =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
        "$Elements\n1\n1 11 2 5 5 1 2 3 4 1 1 1 1 1 1\n$EndElements\n";
    CHECK(parse_msh(tet10, "tet10.msh").tets == std::vector<TetVertices>{{0, 1, 2, 3}});
  }

  TEST_CASE("msh: malformed files are errors that say what and where") {
    const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    check_throws_with("$MeshFormat\n4.0 0 8\n$EndMeshFormat\n", "version 4.0 is not read");
    check_throws_with("$Nodes\n1\n1 0 0 0\n$EndNodes\n", "does not start with $MeshFormat");
    check_throws_with(head + "$Nodes\n2\n1 0 0 0\n", "2 nodes cannot fit in the rest of the file");
    check_throws_with(head + "$Nodes\n1\n1 0 0            \n", "unexpected end of file");
    check_throws_with(head + "$Nodes\n1\n1 0 0 x\n$EndNodes\n", "expected a number");
    check_throws_with(head + "$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 9\n$EndElements\n",
                      "refers to node");
    check_throws_with(head + "$Nodes\n1\n1 0 0 0\n$EndNodes\n", "no $Elements");
    check_throws_with(head + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n$Elements\n0\n$EndElements\n", "appears twice");
    check_throws_with(head + "$Nodes\n99999999999\n", "cannot fit");
    // A binary file cut in the middle of its nodes.
    const std::string binary = read_file_bytes(msh_file("box_sphere_41_binary.msh"));
    check_throws_with(binary.substr(0, binary.size() / 3), "cannot fit in the rest of the file");
    check_throws_with(binary.substr(0, 1000), "truncated");
    // Two tets, one in physical volume 3, the other in none.
    check_throws_with(head +
                          "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n$Elements\n2\n"
                          "1 4 2 3 1 1 2 3 4\n2 4 2 0 2 2 3 4 5\n$EndElements\n",
                      "a tet without a region beside regions");
  }
}
