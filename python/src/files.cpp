#include "files.hpp"

#include "fields.hpp"

#include <metrica/error.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/output_set.hpp>
#include <metrica/io/vtu.hpp>

#include <fmt/core.h>

#include <cmath>

namespace metrica::python {

py::list read_field(const std::string& path) {
  const io::SolData sol = io::read_sol(path);
  py::list out;
  const std::size_t stride = static_cast<std::size_t>(sol.stride());
  std::size_t offset = 0;
  for (const io::SolType t : sol.types) {
    const auto width = static_cast<std::size_t>(io::sol_type_size(t));
    py::array_t<double> a =
        width == 1 ? py::array_t<double>({static_cast<py::ssize_t>(sol.count)})
                   : py::array_t<double>({static_cast<py::ssize_t>(sol.count), static_cast<py::ssize_t>(width)});
    double* x = a.mutable_data();
    for (std::size_t v = 0; v < sol.count; ++v)
      for (std::size_t k = 0; k < width; ++k) *x++ = sol.values[v * stride + offset + k];
    offset += width;
    out.append(a);
  }
  return out;
}

void write_field(const std::string& path, const py::array& values, int version, int expected_width) {
  if (values.dtype().kind() != 'f') throw InputError("write_field: expected float64 values");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  io::SolData sol;
  const py::ssize_t width = a.ndim() == 1 ? 1 : a.ndim() == 2 ? a.shape(1) : 0;
  if (expected_width != 0 && width != expected_width)
    throw InputError(fmt::format("write: expected an (n, {}) metric", expected_width));
  if (width == 1)
    sol.types = {io::SolType::scalar};
  else if (width == 3)
    sol.types = {io::SolType::vector};
  else if (width == 6)
    sol.types = {io::SolType::sym_matrix};
  else
    throw InputError("write_field: expected shape (n,), (n, 3) or (n, 6)");
  sol.count = static_cast<std::size_t>(a.shape(0));
  sol.values.assign(a.data(), a.data() + a.size());
  for (double x : sol.values)
    if (!std::isfinite(x)) throw InputError("write_field: the values are not all finite");
  if (version > 0) sol.version = version;
  io::write_sol(path, sol, version);
}

namespace {

// A point field of the .vtu: (n,) scalar, (n, 3) vector, (n, 6) symmetric
// tensor in libMeshb's order (written in VTK's).
io::VtuField vtu_point_field(const PyMesh& x, const std::string& name, const py::object& values) {
  const auto a = py::array::ensure(values);
  if (!a || (a.ndim() != 1 && a.ndim() != 2))
    throw InputError(fmt::format("write: field '{}' must be an (n,), (n, 3) or (n, 6) array", name));
  const std::size_t width = a.ndim() == 1 ? 0 : static_cast<std::size_t>(a.shape(1));
  if (width != 0 && width != 3 && width != 6)
    throw InputError(fmt::format("write: field '{}' has {} columns (1, 3 or 6 are written)", name, width));
  const std::string what = "write: field '" + name + "'";
  const std::vector<double> by_id = values_by_id(x.mesh(), values, width, what.c_str());
  // Rows in the file's vertex order (the mesh is compact: ids are rows).
  if (width == 6) return io::vtu_tensor_field(name, by_id);
  return {name, width == 0 ? 1 : 3, by_id};
}

}  // namespace

void write_mesh(const PyMesh& x, const std::filesystem::path& path, int version, bool binary, const py::object& metric,
                const py::object& fields) {
  const io::MeshData& data = x.data();  // with the version read (not copied: 25 bytes per tet)
  const std::string ext = path.extension().string();
  const bool vtu = io::format_of(path.string()) == io::FileFormat::vtu;
  if (!fields.is_none() && !vtu)
    throw InputError(
        fmt::format("write: fields= go into a .vtu (got '{}'); write_field writes a .sol/.solb", path.string()));
  if (!metric.is_none() && !vtu && ext != ".mesh" && ext != ".meshb")
    throw InputError(
        fmt::format("write: metric= goes beside a .mesh or .meshb, or into a .vtu (got '{}'); "
                    "write_field writes a .sol/.solb anywhere",
                    path.string()));
  // Finite and positive definite at every vertex, as every reader requires.
  const std::vector<Sym6> m = metric.is_none() ? std::vector<Sym6>{} : metric_by_id(x.mesh(), metric, "write: metric");
  io::OutputSet outputs;
  if (vtu) {
    std::vector<io::VtuField> point_fields;
    if (!metric.is_none()) {
      std::vector<double> flat(6 * m.size());
      for (std::size_t v = 0; v < m.size(); ++v)
        for (int k = 0; k < 6; ++k) flat[6 * v + std::size_t(k)] = m[v][std::size_t(k)];
      point_fields.push_back(io::vtu_tensor_field("metric", flat));
    }
    if (!fields.is_none()) {
      if (!py::isinstance<py::dict>(fields)) throw InputError("write: fields must be a dict of name to array");
      for (const auto& [name, values] : fields.cast<py::dict>())
        point_fields.push_back(
            vtu_point_field(x, py::str(name).cast<std::string>(), py::reinterpret_borrow<py::object>(values)));
    }
    io::write_vtu(path.string(), data, point_fields);
  } else {
    io::write_mesh_file(path.string(), data, version, {}, io::FileFormat::mesh,
                        binary ? io::Encoding::binary : io::Encoding::ascii);
    if (!metric.is_none())
      write_field(std::filesystem::path(path).replace_extension(ext == ".mesh" ? ".sol" : ".solb").string(),
                  metric_array(x.mesh(), m), version, 6);
  }
  outputs.commit();
}

}  // namespace metrica::python
