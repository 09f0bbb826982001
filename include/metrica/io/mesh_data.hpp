// The content of a mesh or solution file, as the file holds it.
//
// This is the exchange layer between the formats and the Mesh: readers fill
// it, writers consume it, and build_mesh() / extract_mesh_data() convert to
// and from the adjacency-rich Mesh. Indices are 0-based here (libMeshb
// files are 1-based; the reader and writer translate).
#pragma once

#include <metrica/ids.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace metrica::io {

// A vertex on a geometric entity (libMeshb VerticesOnGeometricVertices,
// ...Edges, ...Triangles): the entity's id, the parameters there (u = t on
// a curve, (u, v) on a surface; none on a model vertex) and the distance
// the writer measured.
struct GeoRecord {
  VertexId vertex = 0;
  int entity = 0;
  double u = 0.0, v = 0.0, dist = 0.0;
  friend bool operator==(const GeoRecord&, const GeoRecord&) = default;
};

struct MeshData {
  int version = 2;  // libMeshb version read or to write (1-4)
  std::vector<Point> vertices;
  std::vector<int> vertex_refs;
  std::vector<EdgeVertices> edges;
  std::vector<int> edge_refs;
  std::vector<TriangleVertices> triangles;
  std::vector<int> triangle_refs;
  std::vector<TetVertices> tets;
  std::vector<int> tet_refs;
  std::vector<VertexId> corners;            // vertex indices
  std::vector<VertexId> required_vertices;  // vertex indices
  std::vector<std::uint32_t> ridges;        // indices into edges
  // Kept as they are by every operation: not moved, split, flipped or
  // removed (their vertices are required too).
  std::vector<std::uint32_t> required_edges;      // indices into edges
  std::vector<std::uint32_t> required_triangles;  // indices into triangles
  // By entity dimension: on model vertices, curves, surfaces. A vertex may
  // have several records (a curve's vertex on each of its surfaces).
  std::array<std::vector<GeoRecord>, 3> on_geometry;

  friend bool operator==(const MeshData&, const MeshData&) = default;
};

// libMeshb solution types (GmfSca, GmfVec, GmfSymMat, GmfMat).
enum class SolType : int { scalar = 1, vector = 2, sym_matrix = 3, matrix = 4 };

// Number of values of one entry of a type in 3D.
constexpr int sol_type_size(SolType t) {
  switch (t) {
    case SolType::scalar: return 1;
    case SolType::vector: return 3;
    case SolType::sym_matrix: return 6;
    case SolType::matrix: return 9;
  }
  return 0;
}

const char* to_string(SolType t);

// SolAtVertices: one or several fields per vertex, interleaved per vertex
// as the file stores them (all fields of vertex 0, then vertex 1, ...).
// A symmetric tensor is ordered xx, xy, yy, xz, yz, zz.
struct SolData {
  int version = 2;
  std::size_t count = 0;  // number of vertices
  std::vector<SolType> types;
  std::vector<double> values;  // count * stride()

  int stride() const {
    int s = 0;
    for (auto t : types) s += sol_type_size(t);
    return s;
  }
  // Offset of field k inside one vertex's values.
  int offset(std::size_t k) const {
    int s = 0;
    for (std::size_t i = 0; i < k; ++i) s += sol_type_size(types[i]);
    return s;
  }
  // The values of field k, contiguous (count * size of its type).
  std::vector<double> field(std::size_t k) const;

  friend bool operator==(const SolData&, const SolData&) = default;
};

// Every writer refuses a non-finite value (IoError naming `path`, the
// entity and its index): no run reports success with a NaN in its output.
void check_finite(const MeshData& m, const std::string& path);
void check_finite(const SolData& s, const std::string& path);

}  // namespace metrica::io
