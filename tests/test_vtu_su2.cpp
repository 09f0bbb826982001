// The .vtu and .su2 writers and readers.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/io/vtu.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>

using namespace metrica;
using namespace metrica::io;

TEST_SUITE("unit") {
  TEST_CASE("vtu: counts - fields - and a wrong field size is an error") {
    const auto d = box_mesh_data({.nx = 1, .ny = 1, .nz = 1});
    VtuField q{"quality", 1, std::vector<double>(d.tets.size(), 0.5)};
    VtuField m{"metric", 6, std::vector<double>(6 * d.vertices.size(), 1.0)};
    const auto xml = format_vtu(d, {m}, {q});
    // 6 tets and the 12 boundary triangles.
    CHECK(xml.find("NumberOfPoints=\"8\" NumberOfCells=\"18\"") != std::string::npos);
    CHECK(xml.find("Name=\"quality\"") != std::string::npos);
    CHECK(xml.find("Name=\"metric\" NumberOfComponents=\"6\"") != std::string::npos);
    // The appended block as the layout places it: each array's count,
    // then its values (the metric's first entry, the quality of tet 6).
    const VtuLayout layout(8, 6, {{"metric", 6}}, {{"quality", 1}}, 12);
    CHECK(xml.compare(0, layout.head().size(), layout.head()) == 0);
    CHECK(xml.size() == layout.tail_at() + std::string(VtuLayout::tail()).size());
    std::uint64_t count = 0;
    double value = 0.0;
    std::memcpy(&count, xml.data() + layout.count_at(VtuLayout::kFirstPointField), 8);
    CHECK(count == 8 * 6 * 8);
    std::memcpy(&count, xml.data() + layout.count_at(VtuLayout::kConnectivity), 8);
    CHECK(count == 8 * (6 * 4 + 12 * 3));
    std::memcpy(&value, xml.data() + layout.values_at(VtuLayout::kFirstPointField), 8);
    CHECK(value == 1.0);
    std::memcpy(&value, xml.data() + layout.values_at(layout.refs() + 1) + 5 * 8, 8);
    CHECK(value == 0.5);
    std::memcpy(&value, xml.data() + layout.values_at(layout.refs() + 1) + 6 * 8, 8);
    CHECK(std::isnan(value));  // the triangles' entries of a tet field
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

  TEST_CASE("vtu: what the writer writes the reader reads - ids and point fields included") {
    test::TempDir dir;
    auto d = box_mesh_data({.nx = 2, .ny = 1, .nz = 1});
    d.tet_refs.assign(d.tets.size(), 7);
    std::vector<double> m(6 * d.vertices.size());
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = double(i);
    write_vtu(dir / "a.vtu", d, {vtu_tensor_field("metric", m), {"u", 1, std::vector<double>(d.vertices.size(), 2.5)}});
    std::vector<VtuField> fields;
    const MeshData back = read_vtu(dir / "a.vtu", &fields);
    CHECK(back.vertices == d.vertices);
    CHECK(back.tets == d.tets);
    CHECK(back.tet_refs == d.tet_refs);
    CHECK(back.triangles == d.triangles);
    CHECK(back.triangle_refs == d.triangle_refs);
    REQUIRE(fields.size() == 2);
    CHECK(fields[0].name == "metric");
    // VTK's order xx yy zz xy yz xz from libMeshb's xx xy yy xz yz zz.
    CHECK(fields[0].values[0] == 0.0);
    CHECK(fields[0].values[1] == 2.0);
    CHECK(fields[0].values[2] == 5.0);
    CHECK(fields[0].values[3] == 1.0);
    CHECK(fields[0].values[4] == 4.0);
    CHECK(fields[0].values[5] == 3.0);
    CHECK(fields[1].values == std::vector<double>(d.vertices.size(), 2.5));
    CHECK(read_mesh_file(dir / "a.vtu") == back);
    // A count past any file (2^64 - 1 bytes, once a float-to-integer
    // overflow the fuzzer found) is an error, as a wrong one is.
    std::string bytes = format_vtu(d, {}, {});
    const VtuLayout layout(d.vertices.size(), d.tets.size(), {}, {}, d.triangles.size());
    for (const std::uint64_t count : {~std::uint64_t{0}, std::uint64_t{8}}) {
      std::string bad = bytes;
      std::memcpy(bad.data() + layout.count_at(VtuLayout::kPoints), &count, 8);
      CHECK_THROWS_WITH_AS(parse_vtu(bad, "bad.vtu"), doctest::Contains("bytes where"), IoError);
    }
  }

  TEST_CASE("vtu: an ASCII file of another tool is read - compressed or malformed ones are refused") {
    test::TempDir dir;
    const std::string ascii =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<UnstructuredGrid>\n"
        "<Piece NumberOfPoints=\"5\" NumberOfCells=\"3\">\n<Points>\n"
        "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1 1 1 1"
        "</DataArray>\n</Points>\n<Cells>\n"
        "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 0 1 2 1 2</DataArray>\n"
        "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4 7 9</DataArray>\n"
        "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 5 3</DataArray>\n</Cells>\n"
        "<CellData>\n<DataArray type=\"Int32\" Name=\"gmsh:physical\" format=\"ascii\">4 9 0</DataArray>\n"
        "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    write_file_atomically(dir / "a.vtu", ascii);
    const MeshData d = [&] {
      test::QuietLog quiet;  // the line cell is left out with a warning
      return read_vtu(dir / "a.vtu");
    }();
    CHECK(d.vertices.size() == 5);
    REQUIRE(d.tets.size() == 1);
    CHECK(d.tets[0] == TetVertices{0, 1, 2, 3});
    CHECK(d.tet_refs == std::vector<int>{4});
    REQUIRE(d.triangles.size() == 1);
    CHECK(d.triangle_refs == std::vector<int>{9});
    const auto refused = [&](std::string text, const char* says) {
      write_file_atomically(dir / "b.vtu", text);
      CHECK_THROWS_WITH_AS(read_vtu(dir / "b.vtu"), doctest::Contains(says), IoError);
    };
    auto compressed = ascii;
    compressed.replace(compressed.find("version=\"0.1\""), 13, "compressor=\"vtkZLibDataCompressor\"");
    refused(compressed, "compressed");
    auto short_points = ascii;
    short_points.replace(short_points.find(" 1 1 1</DataArray>"), 6, "");
    refused(short_points, "values where 15 are expected");
    auto bad_vertex = ascii;
    bad_vertex.replace(bad_vertex.find("0 1 2 3 0"), 9, "0 1 2 9 0");
    refused(bad_vertex, "names vertex 9");
    refused("<VTKFile type=\"PolyData\">", "UnstructuredGrid");
    refused("not xml", "VTKFile");
  }

  TEST_CASE("su2: what the writer writes the reader reads - named markers get ids - other elements are refused") {
    test::TempDir dir;
    const auto d = box_mesh_data({.nx = 1, .ny = 2, .nz = 1});
    write_su2(dir / "a.su2", d);
    const MeshData back = read_su2(dir / "a.su2");
    CHECK(back.vertices == d.vertices);
    CHECK(back.tets == d.tets);
    CHECK(back.triangles.size() == d.triangles.size());
    // Grouped by marker: the same (triangle, id) pairs.
    std::multiset<std::pair<std::array<VertexId, 3>, int>> a, b;
    for (std::size_t i = 0; i < d.triangles.size(); ++i) a.insert({d.triangles[i], d.triangle_refs[i]});
    for (std::size_t i = 0; i < back.triangles.size(); ++i) b.insert({back.triangles[i], back.triangle_refs[i]});
    CHECK(a == b);
    write_file_atomically(dir / "b.su2",
                          "% a comment\nNDIME= 3\nNELEM= 1\n10 0 1 2 3 0\nNPOIN= 4\n0 0 0 0\n1 0 0 1\n0 1 0 2\n"
                          "0 0 1 3\nNMARK= 2\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n5 0 1 2\n"
                          "MARKER_TAG= farfield\nMARKER_ELEMS= 1\n5 0 1 3\n");
    const MeshData named = [&] {
      test::QuietLog quiet;
      return read_su2(dir / "b.su2");
    }();
    CHECK(named.triangle_refs == std::vector<int>{1001, 1002});
    write_file_atomically(dir / "c.su2", "NDIME= 3\nNELEM= 1\n12 0 1 2 3 4 5 6 7 0\n");
    CHECK_THROWS_WITH_AS(read_su2(dir / "c.su2"), doctest::Contains("only tetrahedra"), IoError);
    write_file_atomically(dir / "d.su2", "NDIME= 3\nNELEM= 1\n10 0 1 2 7 0\nNPOIN= 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
    CHECK_THROWS_WITH_AS(read_su2(dir / "d.su2"), doctest::Contains("names point 7"), IoError);
    write_file_atomically(dir / "e.su2", "NDIME= 3\nNELEM= 2\n10 0 1 2 3 0\n");
    CHECK_THROWS_WITH_AS(read_su2(dir / "e.su2"), doctest::Contains("ends before"), IoError);
  }
}
