// The `metrica._metrica` extension: meshes as numpy arrays, files, metrics
// and the adaptation (python/metrica/__init__.py is the module users
// import).
#include "adaptation.hpp"
#include "fields.hpp"
#include "files.hpp"
#include "mesh_arrays.hpp"
#include "messages.hpp"
#include "pipeline.hpp"

#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/output_set.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/numbering.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/pipeline/composed_pipeline.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <span>

namespace py = pybind11;
using namespace metrica;
using namespace metrica::python;

namespace {
// Rows of the settings table as Python's docstrings read them: (name,
// domain, default, help).
py::list setting_rows(std::span<const AdaptSetting> settings) {
  py::list rows;
  for (const AdaptSetting& s : settings)
    rows.append(py::make_tuple(s.python_name(), s.domain(), s.get(AdaptOptions{}), std::string(s.help)));
  return rows;
}
}  // namespace

PYBIND11_MODULE(_metrica, m) {
  m.doc() = "Metrica: metric-based anisotropic adaptation of tetrahedral meshes";
  auto input_error = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  static_cast<void>(input_error);
  route_messages_to_python();
  // Messages number vertices and tets as numpy rows are (the command's from
  // 1, as libMeshb files do).
  set_first_number(0);
  m.attr("__version__") = METRICA_VERSION;

  py::class_<PyMesh>(m, "Mesh", "A tetrahedral mesh: vertices, tets with region ids, surface triangles with ids.")
      .def(py::init(&mesh_from_arrays), py::arg("points"), py::arg("tets"), py::arg("triangles") = py::none(),
           py::arg("triangle_ids") = py::none(), py::arg("tet_ids") = py::none(), py::kw_only(),
           py::arg("ridge_angle") = py::none(),
           "A mesh from numpy arrays: points float64 (n, 3); tets (m, 4), triangles (k, 3): 0-based vertex "
           "indices; ids int. Checked as a file is (InputError). Without triangles (or with one id for the "
           "whole boundary) the boundary is split into surfaces at edges sharper than 45 degrees, which "
           "become ridges; ridge_angle=DEG splits every surface at DEG degrees (180: none).")
      .def_property_readonly("points", [](const PyMesh& x) { return points_array(x.data()); })
      .def_property_readonly("tets", [](const PyMesh& x) { return tets_array(x.data()); })
      .def_property_readonly("triangles", [](const PyMesh& x) { return triangles_array(x.data()); })
      .def_property_readonly("triangle_ids", [](const PyMesh& x) { return refs_array(x.data().triangle_refs); })
      .def_property_readonly("tet_ids", [](const PyMesh& x) { return refs_array(x.data().tet_refs); })
      .def_property_readonly("num_vertices", [](const PyMesh& x) { return x.mesh().num_vertices(); })
      .def_property_readonly("num_tets", [](const PyMesh& x) { return x.mesh().num_tets(); })
      .def("check", &check_mesh, "Raises InputError with the report when an invariant does not hold.")
      .def("info", &mesh_info, "Counts, extent, volume, surfaces and regions, as `metrica info` prints them.")
      .def("__copy__", [](const PyMesh& x) { return PyMesh(x); })
      .def(
          "__deepcopy__", [](const PyMesh& x, const py::object&) { return PyMesh(x); }, py::arg("memo"))
      .def(py::pickle(&mesh_state, &mesh_from_state))
      .def("__repr__", [](const PyMesh& x) {
        return "<metrica.Mesh: " + std::to_string(x.mesh().num_vertices()) + " vertices, " +
               std::to_string(x.mesh().num_tets()) + " tets>";
      });

  m.def(
      "box",
      [](const py::object& n, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
        BoxSpec spec;
        const auto count = [](const py::handle& k) {
          if (py::isinstance<py::bool_>(k) || !py::isinstance<py::int_>(k))
            throw InputError(
                fmt::format("box: n is a whole number or three (got {})", py::repr(k).cast<std::string>()));
          const long long v = k.cast<long long>();
          return int(std::clamp<long long>(v, -1, 1'000'000));
        };
        if (py::isinstance<py::int_>(n) || py::isinstance<py::bool_>(n)) {
          spec.nx = spec.ny = spec.nz = count(n);
        } else {
          if (!py::isinstance<py::sequence>(n) || py::len(n) != 3)
            throw InputError(
                fmt::format("box: n is a whole number or three (got {})", py::repr(n).cast<std::string>()));
          const auto t = py::reinterpret_borrow<py::sequence>(n);
          spec.nx = count(t[0]), spec.ny = count(t[1]), spec.nz = count(t[2]);
        }
        spec.lo = Point(lo[0], lo[1], lo[2]);
        spec.hi = Point(hi[0], hi[1], hi[2]);
        try {
          check_box_spec(spec);
        } catch (const InputError& e) {
          throw InputError(std::string("box: ") + e.what());
        }
        io::MeshData data = box_mesh_data(spec);
        data.version = 2;
        return mesh_from_file_data(std::move(data), "box", py::none());
      },
      py::arg("n") = 3, py::arg("lo") = std::array<double, 3>{0, 0, 0}, py::arg("hi") = std::array<double, 3>{1, 1, 1},
      "The box [lo, hi] of n x n x n hexes (n: one count or three), each split into 6 tets (Kuhn), with the UGAWG "
      "cube's surface ids (1 x = lo, 2 x = hi, 3, 4 in y, 5, 6 in z): `metrica cube`. n = 3 is the UGAWG start mesh.");

  using Path = std::filesystem::path;
  m.def(
      "read", [](const Path& path, const py::object& ridge_angle) { return read_mesh(path.string(), ridge_angle); },
      py::arg("path"), py::kw_only(), py::arg("ridge_angle") = py::none(),
      "A mesh file (.mesh, .meshb, .msh, .vtu, .su2), checked as every command reads it; ridge_angle as for Mesh().");
  m.def("write", &write_mesh, py::arg("mesh"), py::arg("path"), py::arg("version") = 0, py::arg("binary") = false,
        py::arg("metric") = py::none(), py::arg("fields") = py::none(),
        "Writes .mesh, .meshb (libMeshb version: 0 keeps the one read), .msh (4.1, or 2.2 with version=2; "
        "binary=True for binary), .vtu or .su2, through a temporary renamed when complete. metric, an (n, 6) "
        "array: beside a .mesh/.meshb as the .sol/.solb of the same name (both replaced together), in a .vtu "
        "as the point data \"metric\" (VTK's tensor order, for ParaView). fields (.vtu only): a dict of name to "
        "(n,), (n, 3) or (n, 6) arrays, written as point data.");
  m.def(
      "read_field", [](const Path& path) { return read_field(path.string()); }, py::arg("path"),
      "The fields of a .sol/.solb: a list of arrays, (n,), (n, 3) or (n, 6) (xx, xy, yy, xz, yz, zz).");
  m.def(
      "write_field",
      [](const Path& path, const py::array& values, int version) { write_field(path.string(), values, version); },
      py::arg("path"), py::arg("values"), py::arg("version") = 0,
      "Writes one field to a .sol/.solb: (n,) scalar, (n, 3) vector, (n, 6) symmetric tensor.");
  m.def("analytic_metric", &analytic_metric, py::arg("mesh"), py::arg("name"), py::arg("hmin") = py::none(),
        py::arg("hmax") = py::none(), "The analytic metric (linear, polar-1, polar-2) at the mesh's vertices, (n, 6).");
  m.def("analytic_field", &analytic_field, py::arg("mesh"), py::arg("name"),
        "An analytic field of `metrica metric --field` at the mesh's vertices, (n,).");
  // The parameters shared by the two multiscale metrics' docstrings.
  static const std::string multiscale_parameters =
      "complexity: the metric's complexity N, which sets the adapted mesh's size (about 2 N vertices and 10 N "
      "tets on the UGAWG cube); "
      "norm: p of the L^p norm the error is minimised in (default 2; >= 1; larger p weighs weak features "
      "more); gradation: the size gradation bound beta (None: no gradation; e.g. 1.5 to 3, >= 1); hmin, "
      "hmax: bounds on the sizes asked for (None: 0 and the domain's largest extent); max_anisotropy: bound "
      "on the ratio of largest to smallest size at a vertex (None: unbounded).";
  m.def("multiscale_metric", &multiscale_metric, py::arg("mesh"), py::arg("field"), py::arg("complexity"),
        py::arg("norm") = 2.0, py::arg("gradation") = py::none(), py::arg("hmin") = py::none(),
        py::arg("hmax") = py::none(), py::arg("max_anisotropy") = py::none(),
        ("The multiscale metric (Loseille and Alauzet) of a P1 field (n,), or of k fields (n, k) each scaled to "
         "the complexity then intersected, the Hessian recovered by L2 projection (`metrica metric --field-file`): "
         "(n, 6). " +
         multiscale_parameters)
            .c_str());
  m.def("hessian", &hessian, py::arg("mesh"), py::arg("field"),
        "The Hessian of a P1 field (n,) recovered by L2 projection (twice), as the multiscale metric uses it: "
        "(n, 6) symmetric tensors (xx, xy, yy, xz, yz, zz).");
  m.def("hessian_metric", &hessian_metric, py::arg("mesh"), py::arg("hessian"), py::arg("complexity"),
        py::arg("norm") = 2.0, py::arg("gradation") = py::none(), py::arg("hmin") = py::none(),
        py::arg("hmax") = py::none(), py::arg("max_anisotropy") = py::none(),
        ("The multiscale metric of a Hessian field (n, 6) the caller gives (a solver's own, or metrica.hessian's): "
         "the absolute values of its eigenvalues, scaled to the complexity, bounded and graded as "
         "multiscale_metric does. " +
         multiscale_parameters)
            .c_str());
  m.def("intersect", &intersect, py::arg("a"), py::arg("b"), "The metric intersection of two (n, 6) fields.");
  m.def("complexity", &complexity, py::arg("mesh"), py::arg("metric"), "The complexity of an (n, 6) metric.");
  m.def("interpolate", &interpolate, py::arg("mesh"), py::arg("field"), py::arg("to_mesh"), py::arg("metric") = false,
        "The P1 interpolant of a field (n,) or (n, k) on `mesh` at the vertices of `to_mesh`; with metric=True "
        "the field is (n, 6) symmetric tensors, moved log-Euclidean (exp of the interpolant of log M).");
  m.def("error", &l2_error, py::arg("mesh"), py::arg("values"), py::arg("exact") = py::none(),
        py::arg("reference") = py::none(), py::arg("reference_values") = py::none(),
        "The L2 error of a P1 field (values, (n,)): against exact, an analytic field's name (`metrica metric "
        "--field`) or a function of a (k, 3) array of points returning k values (called on blocks of quadrature "
        "points, degree 5); or against a reference mesh's field (reference, reference_values, or exact at its "
        "vertices), the field carried there first.");
  m.def("quality", &quality, py::arg("mesh"), py::arg("metric"), py::arg("space") = "log-euclidean",
        py::arg("measures") = true, py::arg("metric_mesh") = py::none(),
        "The UGAWG quality report of the mesh in the metric, as a dict; with measures, also \"edge_ends\" "
        "(k, 2), \"edge_lengths\" (k,) and \"mean_ratios\" (one per tet, in the order of mesh.tets). With "
        "metric_mesh, the metric is given at that mesh's vertices and interpolated log-Euclidean at this one's.");
  m.def(
      "_adapt_settings", [] { return setting_rows(adapt_settings()); },
      "The settings adapt takes by name: (name, domain, default, help) rows of the command's table.");
  m.def(
      "_pipeline_rules", [] { return setting_rows(pipeline_rule_settings()); },
      "The rules a Pipeline takes by name: (name, domain, default, help) rows of the command's table.");
  m.def(
      "_stage_kinds",
      [] {
        py::list kinds;
        for (const StageKindInfo& k : stage_kind_infos()) {
          py::list options;
          for (const StageOption& o : k.options)
            options.append(py::make_tuple(std::string(o.name), o.domain(), std::string(o.help)));
          kinds.append(py::make_tuple(std::string(k.op), std::string(k.help), options));
        }
        return kinds;
      },
      "The kinds of stage a Pipeline takes: (operation, help, [(option, domain, help)]) rows of the registry.");
  m.def(
      "_adapt",
      [](const PyMesh& x, py::object metric, std::string analytic, int iterations, int threads, std::string concurrency,
         std::string space, std::string precision, std::string geometry, py::dict options, py::object on_cycle,
         double max_tets, bool dry_run) {
        AdaptCall call;
        call.metric = std::move(metric);
        call.analytic = std::move(analytic);
        call.iterations = iterations;
        call.threads = threads;
        call.concurrency = std::move(concurrency);
        call.space = std::move(space);
        call.precision = std::move(precision);
        call.geometry = std::move(geometry);
        call.options = std::move(options);
        call.on_cycle = std::move(on_cycle);
        call.max_tets = max_tets;
        call.dry_run = dry_run;
        return adapt(x, call);
      },
      py::arg("mesh"), py::arg("metric"), py::arg("analytic"), py::arg("iterations"), py::arg("threads"),
      py::arg("concurrency"), py::arg("space"), py::arg("precision"), py::arg("geometry"), py::arg("options"),
      py::arg("on_cycle"), py::arg("max_tets"), py::arg("dry_run"));
  m.def(
      "_run_pipeline",
      [](const PyMesh& x, py::object metric, std::string analytic, py::list cycle, py::list polish, py::list repair,
         py::dict rules, std::string concurrency, int threads, py::object on_cycle) {
        auto specs = [](const py::list& list) {
          std::vector<PyStageSpec> out;
          for (const auto& item : list) {
            const auto t = item.cast<py::tuple>();
            out.push_back({t[0].cast<std::string>(), t[1].cast<std::string>(), t[2].cast<py::dict>()});
          }
          return out;
        };
        PipelineCall call;
        call.metric = std::move(metric);
        call.analytic = std::move(analytic);
        call.cycle = specs(cycle);
        call.polish = specs(polish);
        call.repair = specs(repair);
        call.rules = std::move(rules);
        call.concurrency = std::move(concurrency);
        call.threads = threads;
        call.on_cycle = std::move(on_cycle);
        return run_pipeline(x, call);
      },
      py::arg("mesh"), py::arg("metric"), py::arg("analytic"), py::arg("cycle"), py::arg("polish"), py::arg("repair"),
      py::arg("rules"), py::arg("concurrency"), py::arg("threads"), py::arg("on_cycle"));
}
