// VTK unstructured grid (.vtu) for ParaView: tets, then the surface
// triangles, with per-vertex and per-tet fields, the arrays as raw appended
// data; and a reader of such files (ours, or any with tets and triangles as
// raw appended, base64 or ASCII data without compression). VtuLayout is the one
// description of the file (its XML head, where each array's bytes go):
// the single-process writer fills it at once, the MPI writer
// (distributed/write_part.cpp) places each rank's slices in it.
#pragma once

#include <metrica/io/mesh_data.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace metrica::io {

struct VtuField {
  std::string name;
  int components = 1;          // 1 scalar, 3 vector, 6 or 9 tensor
  std::vector<double> values;  // size = entities * components
};

// The arrays of a tet grid's .vtu, in file order: the points (Float64 x 3),
// the cells (the tets then the triangles: connectivity Int64 x 4 a tet and
// x 3 a triangle, offsets Int64, types UInt8), then the point fields
// (Float64), the cells' refs (Int32: region and surface ids) and the cell
// fields (Float64). Each array in the appended block is an 8-byte count
// (UInt64) and its bytes.
class VtuLayout {
 public:
  struct Array {
    std::string type, name;
    int components;
    std::uint64_t bytes;   // of the values
    std::uint64_t offset;  // of its count in the appended block
  };
  // The first arrays' indices.
  enum : std::size_t { kPoints = 0, kConnectivity = 1, kOffsets = 2, kTypes = 3, kFirstPointField = 4 };
  struct FieldShape {
    std::string name;
    int components;
  };
  VtuLayout(std::uint64_t vertices, std::uint64_t tets, const std::vector<FieldShape>& point_fields = {},
            const std::vector<FieldShape>& cell_fields = {}, std::uint64_t triangles = 0);

  const std::vector<Array>& arrays() const { return arrays_; }
  std::size_t refs() const { return kFirstPointField + point_fields_; }  // the "ref" array's index
  // The XML up to the appended block's first byte, and after its last.
  const std::string& head() const { return head_; }
  static const char* tail() { return "\n  </AppendedData>\n</VTKFile>\n"; }
  // Where array k's count and its values start in the file.
  std::uint64_t count_at(std::size_t k) const { return head_.size() + arrays_[k].offset; }
  std::uint64_t values_at(std::size_t k) const { return count_at(k) + 8; }
  // Array k's count as it is written at count_at(k) (8 bytes, this
  // machine's order, as the values are).
  std::string count_bytes(std::size_t k) const {
    return std::string(reinterpret_cast<const char*>(&arrays_[k].bytes), sizeof(std::uint64_t));
  }
  std::uint64_t tail_at() const;

 private:
  std::vector<Array> arrays_;
  std::size_t point_fields_ = 0;
  std::string head_;
};

// Writes the tets and triangles of `mesh` (their region and surface ids as
// the cell field "ref"), plus the given point fields (one entry per vertex;
// a symmetric tensor in VTK's order xx, yy, zz, xy, yz, xz) and cell fields
// (one entry per tet; NaN on the triangles). Written through a temporary
// file and renamed.
void write_vtu(const std::string& path, const MeshData& mesh, const std::vector<VtuField>& point_fields = {},
               const std::vector<VtuField>& cell_fields = {});

std::string format_vtu(const MeshData& mesh, const std::vector<VtuField>& point_fields,
                       const std::vector<VtuField>& cell_fields);

// A symmetric tensor field from libMeshb's order (xx, xy, yy, xz, yz, zz)
// to VTK's, as ParaView reads 6 components.
VtuField vtu_tensor_field(std::string name, const std::vector<double>& meshb_order);

// Reads a .vtu's tets (type 10) and triangles (type 5) with the cell field
// "ref" (or "medit:ref", "gmsh:physical") as their ids; other cells are left
// out with a warning. The point fields go to `point_fields` when given.
// IoError for compressed data, other encodings or a malformed file.
MeshData read_vtu(const std::string& path, std::vector<VtuField>* point_fields = nullptr);
// The same from the file's bytes (`path` names it in messages).
MeshData parse_vtu(std::string bytes, const std::string& path, std::vector<VtuField>* point_fields = nullptr);

}  // namespace metrica::io
