// Meshes between numpy arrays and Metrica: the Python Mesh object, built
// from arrays or a file, and its arrays back (owned by numpy, copied out of
// the file's layout: 0-based indices, ids as int32).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

#include <array>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace metrica::python {

namespace py = pybind11;

// A mesh as Python holds it: the adjacency-rich Mesh, the libMeshb version
// it was read with (written back the same, as the command does), and its
// file layout, made when an array is first asked for. A mesh read from a
// file keeps the file's association with a CAD model (its vertices'
// entities and parameters, which the Mesh holds only once associated with
// a model): written back, or adapted on that model, as the command does.
class PyMesh {
 public:
  using GeoRecords = std::array<std::vector<io::GeoRecord>, 3>;
  PyMesh(Mesh mesh, int version, GeoRecords read_records = {})
      : mesh_(std::move(mesh)), version_(version), read_records_(std::move(read_records)) {}
  const Mesh& mesh() const { return mesh_; }
  int version() const { return version_; }
  const GeoRecords& read_records() const { return read_records_; }
  // The file layout (vertex ids ascending, removed ones skipped), with the
  // libMeshb version read.
  const io::MeshData& data() const;

 private:
  Mesh mesh_;
  int version_;
  GeoRecords read_records_;  // the file's, for a mesh read (its ids are the file's)
  mutable std::optional<io::MeshData> data_;
};

// Mesh(points, tets, triangles, triangle_ids, tet_ids): the arrays (or
// lists of rows) checked (shapes, dtypes, indices in range, finite
// coordinates), then the mesh
// built and checked like a file's (InputError with the command's message).
// Without triangles (or with one id for the whole boundary) the surfaces
// are split at edges sharper than 45 degrees; `ridge_angle` (degrees, not
// None) splits every surface so (surface_angles.hpp).
PyMesh mesh_from_arrays(const py::object& points, const py::object& tets, const py::object& triangles,
                        const py::object& triangle_ids, const py::object& tet_ids, const py::object& ridge_angle);

// A file read and checked as every command reads its input.
PyMesh read_mesh(const std::string& path, const py::object& ridge_angle);
// A file's content checked and built as read_mesh does (`path` names it
// in messages).
PyMesh mesh_from_file_data(io::MeshData data, const std::string& path, const py::object& ridge_angle);

// The pickle state of a mesh, its file layout as libMeshb bytes (version
// 4, with the association records) and the version it was read with, and
// the mesh made again from it (built and checked as a file is).
py::tuple mesh_state(const PyMesh& m);
PyMesh mesh_from_state(const py::tuple& state);

// The mesh's arrays.
py::array_t<double> points_array(const io::MeshData& d);
py::array_t<std::int32_t> tets_array(const io::MeshData& d);
py::array_t<std::int32_t> triangles_array(const io::MeshData& d);
py::array_t<std::int32_t> refs_array(const std::vector<int>& refs);

// check(): InputError with validate()'s report; info(): counts, volume,
// surfaces and regions as a dict.
void check_mesh(const PyMesh& m);
py::dict mesh_info(const PyMesh& m);

}  // namespace metrica::python
