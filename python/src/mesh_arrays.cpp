#include "mesh_arrays.hpp"

#include <metrica/error.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_summary.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cstring>
#include <limits>

namespace metrica::python {

namespace {

// The array `a` as a C-contiguous (rows, width) array of T: InputError
// naming `what` for another shape or a dtype of another kind (a float for
// indices; coordinates may be any real or integer type).
template <class T>
py::array_t<T, py::array::c_style> as_rows(const py::array& a, std::size_t width, const char* what) {
  const bool want_float = std::is_floating_point_v<T>;
  const char kind = a.dtype().kind();
  const bool ok_kind = kind == 'i' || kind == 'u' || (want_float && kind == 'f');
  if (!ok_kind)
    throw InputError(fmt::format("{}: expected {} values, got dtype {}", what, want_float ? "float64" : "integer",
                                 py::str(a.dtype()).cast<std::string>()));
  const bool rows = width == 0 ? a.ndim() == 1 : a.ndim() == 2 && static_cast<std::size_t>(a.shape(1)) == width;
  if (!rows) {
    std::string shape;
    for (py::ssize_t k = 0; k < a.ndim(); ++k) shape += fmt::format("{}{}", k > 0 ? ", " : "", a.shape(k));
    throw InputError(fmt::format("{}: expected shape {}, got ({})", what,
                                 width == 0 ? std::string("(n,)") : fmt::format("(n, {})", width), shape));
  }
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
}

// `x` as a numpy array (a list of rows, any sequence numpy takes);
// TypeError naming `what` for what is not array-like.
py::array array_like(const py::object& x, const char* what) {
  py::array a = py::array::ensure(x);
  if (!a || a.dtype().kind() == 'O') {  // numpy holds anything else as objects
    PyErr_Clear();
    throw py::type_error(fmt::format("{}: expected an array or a sequence of rows, got {}", what,
                                     py::str(py::type::of(x).attr("__name__")).cast<std::string>()));
  }
  return a;
}

// Index rows checked against `vertices` (0-based).
template <std::size_t N>
std::vector<std::array<VertexId, N>> index_rows(const py::array& a, std::size_t vertices, const char* what) {
  const auto rows = as_rows<std::int64_t>(a, N, what);
  const auto r = rows.template unchecked<2>();
  std::vector<std::array<VertexId, N>> out(static_cast<std::size_t>(rows.shape(0)));
  for (py::ssize_t i = 0; i < rows.shape(0); ++i)
    for (std::size_t k = 0; k < N; ++k) {
      const std::int64_t v = r(i, static_cast<py::ssize_t>(k));
      if (v < 0 || static_cast<std::uint64_t>(v) >= vertices)
        throw InputError(fmt::format("{}: row {} holds vertex {}, out of range [0, {})", what, i, v, vertices));
      out[static_cast<std::size_t>(i)][k] = static_cast<VertexId>(v);
    }
  return out;
}

std::vector<int> id_column(const py::object& o, std::size_t rows, const char* what) {
  if (o.is_none()) return std::vector<int>(rows, 0);
  const auto ids = as_rows<std::int64_t>(py::array::ensure(o), 0, what);
  if (static_cast<std::size_t>(ids.shape(0)) != rows)
    throw InputError(fmt::format("{}: {} ids for {} rows", what, ids.shape(0), rows));
  std::vector<int> out(rows);
  const auto r = ids.unchecked<1>();
  for (std::size_t i = 0; i < rows; ++i) {
    const std::int64_t v = r(static_cast<py::ssize_t>(i));
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      throw InputError(fmt::format("{}: id {} of row {} does not fit an int", what, v, i));
    out[i] = static_cast<int>(v);
  }
  return out;
}

template <class T>
py::array_t<T> new_array(std::size_t rows, std::size_t width) {
  return width == 0 ? py::array_t<T>({static_cast<py::ssize_t>(rows)})
                    : py::array_t<T>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(width)});
}

template <std::size_t N>
py::array_t<std::int32_t> index_array(const std::vector<std::array<VertexId, N>>& rows) {
  auto out = new_array<std::int32_t>(rows.size(), N);
  auto w = out.template mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t k = 0; k < N; ++k)
      w(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = static_cast<std::int32_t>(rows[i][k]);
  return out;
}

}  // namespace

const io::MeshData& PyMesh::data() const {
  if (!data_) {
    data_ = extract_mesh_data(mesh_);
    data_->version = version_;
    for (std::size_t k = 0; k < 3; ++k)
      if (data_->on_geometry[k].empty()) data_->on_geometry[k] = read_records_[k];
  }
  return *data_;
}

namespace {
// ridge_angle=DEG: every surface split at DEG degrees (0 to 180).
void set_ridge_angle(BuildOptions& o, const py::object& ridge_angle) {
  if (ridge_angle.is_none()) return;
  const double a = py::cast<double>(ridge_angle);
  if (!(a >= 0.0 && a <= 180.0)) throw InputError(fmt::format("ridge_angle: {} is not in [0, 180] degrees", a));
  o.ridge_angle = a;
  o.split_every_surface = true;
}
}  // namespace

PyMesh mesh_from_arrays(const py::object& points, const py::object& tets, const py::object& triangles,
                        const py::object& triangle_ids, const py::object& tet_ids, const py::object& ridge_angle) {
  io::MeshData d;
  const auto p = as_rows<double>(array_like(points, "points"), 3, "points");
  if (static_cast<std::uint64_t>(p.shape(0)) >= std::numeric_limits<std::int32_t>::max())
    throw InputError("points: more vertices than 32-bit ids hold");
  d.vertices.resize(static_cast<std::size_t>(p.shape(0)));
  std::memcpy(static_cast<void*>(d.vertices.data()), p.data(), sizeof(double) * 3 * d.vertices.size());
  d.vertex_refs.assign(d.vertices.size(), 0);
  d.tets = index_rows<4>(array_like(tets, "tets"), d.vertices.size(), "tets");
  d.tet_refs = id_column(tet_ids, d.tets.size(), "tet_ids");
  if (!triangles.is_none()) {
    d.triangles = index_rows<3>(array_like(triangles, "triangles"), d.vertices.size(), "triangles");
    d.triangle_refs = id_column(triangle_ids, d.triangles.size(), "triangle_ids");
  } else if (!triangle_ids.is_none()) {
    throw InputError("triangle_ids given without triangles");
  }
  check_coordinates(d, "points");
  BuildOptions o;
  o.source = "the arrays";
  o.require_boundary_triangles = !triangles.is_none();
  set_ridge_angle(o, ridge_angle);
  Mesh mesh = build_mesh(d, o);
  check_valid_input(mesh, "the arrays");
  return PyMesh(std::move(mesh), d.version);
}

PyMesh read_mesh(const std::string& path, const py::object& ridge_angle) {
  return mesh_from_file_data(io::read_mesh_file(path), path, ridge_angle);
}

PyMesh mesh_from_file_data(io::MeshData d, const std::string& path, const py::object& ridge_angle) {
  check_coordinates(d, path);
  BuildOptions o;
  o.source = path;
  o.require_boundary_triangles = true;
  set_ridge_angle(o, ridge_angle);
  Mesh mesh = build_mesh(d, o);
  check_valid_input(mesh, path);
  return PyMesh(std::move(mesh), d.version, std::move(d.on_geometry));
}

py::tuple mesh_state(const PyMesh& m) {
  // Without Corners: a file's corners are read as required vertices, and
  // the mesh's own are found again from its ridges; those required are
  // among the RequiredVertices.
  io::MeshData d = m.data();
  d.corners.clear();
  return py::make_tuple(py::bytes(io::format_mesh(d, io::Encoding::binary, 4)), m.version());
}

PyMesh mesh_from_state(const py::tuple& state) {
  if (state.size() != 2 || !py::isinstance<py::bytes>(state[0]) || !py::isinstance<py::int_>(state[1]))
    throw InputError("Mesh: a pickled mesh is (libMeshb bytes, version)");
  const std::string bytes = state[0].cast<std::string>();
  PyMesh m =
      mesh_from_file_data(io::parse_mesh(bytes, io::Encoding::binary, "a pickled mesh"), "a pickled mesh", py::none());
  return PyMesh(m.mesh(), state[1].cast<int>(), m.read_records());
}

py::array_t<double> points_array(const io::MeshData& d) {
  auto out = new_array<double>(d.vertices.size(), 3);
  std::memcpy(out.mutable_data(), static_cast<const void*>(d.vertices.data()), sizeof(double) * 3 * d.vertices.size());
  return out;
}

py::array_t<std::int32_t> tets_array(const io::MeshData& d) { return index_array<4>(d.tets); }
py::array_t<std::int32_t> triangles_array(const io::MeshData& d) { return index_array<3>(d.triangles); }

py::array_t<std::int32_t> refs_array(const std::vector<int>& refs) {
  auto out = new_array<std::int32_t>(refs.size(), 0);
  std::copy(refs.begin(), refs.end(), out.mutable_data());
  return out;
}

void check_mesh(const PyMesh& m) {
  const auto report = m.mesh().validate();
  if (!report.ok()) throw InputError(fmt::format("the mesh is invalid\n{}", report.to_string()));
}

py::dict mesh_info(const PyMesh& m) {
  const MeshSummary s = summarize(m.mesh());
  py::dict surfaces, regions;
  for (const auto& [id, x] : s.surfaces)
    surfaces[py::int_(id)] =
        py::dict(py::arg("faces") = x.faces, py::arg("area") = x.area, py::arg("internal") = x.internal);
  for (const auto& [id, x] : s.regions)
    regions[py::int_(id)] = py::dict(py::arg("tets") = x.tets, py::arg("volume") = x.volume);
  py::dict out;
  out["vertices"] = s.vertices;
  out["tets"] = s.tets;
  out["boundary_faces"] = s.boundary_faces;
  out["internal_faces"] = s.internal_faces;
  out["corners"] = s.corners;
  out["ridge_edges"] = s.ridge_edges;
  out["ridge_curves"] = s.ridge_curves;
  out["required_vertices"] = s.required_vertices;
  out["volume"] = s.volume;
  out["min_tet_volume"] = s.min_tet_volume;
  out["max_tet_volume"] = s.max_tet_volume;
  out["bounds"] =
      py::make_tuple(py::make_tuple(s.lo.x(), s.lo.y(), s.lo.z()), py::make_tuple(s.hi.x(), s.hi.y(), s.hi.z()));
  out["surfaces"] = surfaces;
  out["regions"] = regions;
  return out;
}

}  // namespace metrica::python
