// Files from Python besides the meshes (mesh_arrays.hpp reads those): the
// fields of .sol/.solb files, and a mesh written with its metric and fields.
#pragma once

#include "mesh_arrays.hpp"

#include <filesystem>
#include <string>

namespace metrica::python {

// The fields of a .sol/.solb: one array per field, (n,), (n, 3) or (n, 6).
py::list read_field(const std::string& path);
// One field written: (n,) scalar, (n, 3) vector, (n, 6) symmetric tensor
// (`width`, when not 0, the one expected).
void write_field(const std::string& path, const py::array& values, int version, int width = 0);

// `metrica.write`: the mesh in the format of `path`'s extension; the
// metric ((n, 6)) beside a .mesh/.meshb as its .sol/.solb, or in a .vtu as
// point data with `fields` (a dict of name to (n,), (n, 3), (n, 6)); every
// file through a temporary, all renamed together.
void write_mesh(const PyMesh& x, const std::filesystem::path& path, int version, bool binary, const py::object& metric,
                const py::object& fields);

}  // namespace metrica::python
