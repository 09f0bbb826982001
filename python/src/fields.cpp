#include "fields.hpp"

#include <metrica/error.hpp>
#include <metrica/metrics/analytic_field.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/interpolation_error.hpp>
#include <metrica/metrics/intersection.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/metrics/recovery.hpp>
#include <metrica/numbering.hpp>
#include <metrica/point_location.hpp>

#include <fmt/core.h>

#include <cmath>
#include <cstring>

namespace metrica::python {

namespace {

// A C-contiguous float64 copy-free view of `values` when it is one, after
// the shape checks.
py::array_t<double, py::array::c_style> float_rows(const py::object& values, std::size_t width, const char* what) {
  const auto a = py::array::ensure(values);
  if (!a || a.dtype().kind() != 'f') throw InputError(fmt::format("{}: expected a float64 array", what));
  const bool ok = width == 0 ? a.ndim() == 1 : a.ndim() == 2 && static_cast<std::size_t>(a.shape(1)) == width;
  if (!ok)
    throw InputError(
        fmt::format("{}: expected shape {}", what, width == 0 ? std::string("(n,)") : fmt::format("(n, {})", width)));
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

// The width of a field array: (n,) is 0, (n, k) is k.
std::size_t width_of(const py::object& values, const char* what) {
  const auto a = py::array::ensure(values);
  if (!a || (a.ndim() != 1 && a.ndim() != 2)) throw InputError(fmt::format("{}: expected shape (n,) or (n, k)", what));
  return a.ndim() == 1 ? 0 : static_cast<std::size_t>(a.shape(1));
}

}  // namespace

MetricBounds bounds_of(const py::object& hmin, const py::object& hmax) {
  MetricBounds b;
  if (!hmin.is_none()) b.hmin = hmin.cast<double>();
  if (!hmax.is_none()) b.hmax = hmax.cast<double>();
  if (!(b.hmin >= 0.0) || !(b.hmax > 0.0) || b.hmin > b.hmax)
    throw InputError(fmt::format("need 0 <= hmin <= hmax, hmax > 0 (got {} and {})", b.hmin, b.hmax));
  return b;
}

std::vector<Point> vertex_points(const Mesh& mesh) {
  std::vector<Point> points(mesh.vertex_capacity(), Point::Zero());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) points[v] = mesh.point(v);
  return points;
}

std::vector<double> values_by_id(const Mesh& mesh, const py::object& values, std::size_t width, const char* what) {
  const auto a = float_rows(values, width, what);
  const std::size_t w = std::max<std::size_t>(width, 1);
  if (static_cast<std::size_t>(a.shape(0)) != mesh.num_vertices())
    throw InputError(fmt::format("{}: {} rows for {} vertices", what, a.shape(0), mesh.num_vertices()));
  std::vector<double> out(mesh.vertex_capacity() * w, 0.0);
  const double* x = a.data();
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    for (std::size_t k = 0; k < w; ++k, ++x) {
      if (!std::isfinite(*x))
        throw InputError(fmt::format("{}: a value of vertex {} is not finite", what, numbered(v)));
      out[v * w + k] = *x;
    }
  }
  return out;
}

py::array_t<double> values_array(const Mesh& mesh, const std::vector<double>& by_id, std::size_t width) {
  const std::size_t w = std::max<std::size_t>(width, 1);
  const auto n = static_cast<py::ssize_t>(mesh.num_vertices());
  py::array_t<double> out = width == 0 ? py::array_t<double>({n}) : py::array_t<double>({n, py::ssize_t(width)});
  double* x = out.mutable_data();
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) {
      std::memcpy(x, by_id.data() + v * w, sizeof(double) * w);
      x += w;
    }
  return out;
}

std::vector<Sym6> metric_by_id(const Mesh& mesh, const py::object& metric, const char* what, bool check) {
  const std::vector<double> flat = values_by_id(mesh, metric, 6, what);
  std::vector<Sym6> out(mesh.vertex_capacity(), Sym6{1, 0, 1, 0, 0, 1});
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) std::memcpy(out[v].data(), flat.data() + 6 * v, sizeof(Sym6));
  if (check) check_metric_field(out, what);
  return out;
}

py::array_t<double> metric_array(const Mesh& mesh, const std::vector<Sym6>& by_id) {
  std::vector<double> flat(6 * by_id.size());
  for (std::size_t v = 0; v < by_id.size(); ++v) std::memcpy(flat.data() + 6 * v, by_id[v].data(), sizeof(Sym6));
  return values_array(mesh, flat, 6);
}

py::array_t<double> analytic_metric(const PyMesh& m, const std::string& name, const py::object& hmin,
                                    const py::object& hmax) {
  const AnalyticMetric kind = analytic_metric_from_name(name);
  std::vector<Sym6> field = analytic_metric_field(kind, vertex_points(m.mesh()));
  clamp_metrics(field, bounds_of(hmin, hmax));
  check_metric_field(field, fmt::format("metric '{}'", name));
  return metric_array(m.mesh(), field);
}

py::array_t<double> analytic_field(const PyMesh& m, const std::string& name) {
  const AnalyticField kind = analytic_field_from_name(name);
  const auto values = values_at_vertices(m.mesh(), [kind](const Point& p) { return evaluate(kind, p); });
  return values_array(m.mesh(), values, 0);
}

namespace {

MultiscaleOptions multiscale_options(const char* what, double complexity, double norm, const py::object& gradation,
                                     const py::object& hmin, const py::object& hmax,
                                     const py::object& max_anisotropy) {
  MultiscaleOptions o;
  if (!(complexity > 0.0 && std::isfinite(complexity)))
    throw InputError(fmt::format("{}: complexity must be > 0 (got {})", what, complexity));
  if (!(norm >= 1.0 && std::isfinite(norm)))
    throw InputError(fmt::format("{}: norm must be >= 1 (got {})", what, norm));
  o.complexity = complexity;
  o.norm = norm;
  o.bounds = bounds_of(hmin, hmax);
  if (!max_anisotropy.is_none()) {
    o.bounds.max_anisotropy = max_anisotropy.cast<double>();
    if (!(o.bounds.max_anisotropy >= 1.0))
      throw InputError(fmt::format("{}: max_anisotropy must be >= 1 (got {})", what, o.bounds.max_anisotropy));
  }
  o.gradation = !gradation.is_none();
  if (o.gradation) {
    o.gradation_options.beta = gradation.cast<double>();
    if (!(o.gradation_options.beta >= 1.0))
      throw InputError(fmt::format("{}: gradation must be >= 1 (got {})", what, o.gradation_options.beta));
  }
  return o;
}

}  // namespace

py::array_t<double> multiscale_metric(const PyMesh& m, const py::object& field, double complexity, double norm,
                                      const py::object& gradation, const py::object& hmin, const py::object& hmax,
                                      const py::object& max_anisotropy) {
  const Mesh& mesh = m.mesh();
  const MultiscaleOptions o =
      multiscale_options("multiscale_metric", complexity, norm, gradation, hmin, hmax, max_anisotropy);
  const std::size_t width = width_of(field, "field");
  const std::vector<double> flat = values_by_id(mesh, field, width, "field");
  std::vector<Sym6> metric;
  if (width <= 1) {
    metric = multiscale_metric(mesh, flat, o);
  } else {
    std::vector<std::vector<double>> fields(width, std::vector<double>(mesh.vertex_capacity(), 0.0));
    for (std::size_t v = 0; v < mesh.vertex_capacity(); ++v)
      for (std::size_t k = 0; k < width; ++k) fields[k][v] = flat[v * width + k];
    metric = multiscale_metric(mesh, fields, o);
  }
  return metric_array(mesh, metric);
}

py::array_t<double> hessian(const PyMesh& m, const py::object& field) {
  const Mesh& mesh = m.mesh();
  return metric_array(mesh, recover_hessian(mesh, values_by_id(mesh, field, 0, "hessian: field")));
}

py::array_t<double> hessian_metric(const PyMesh& m, const py::object& hessian, double complexity, double norm,
                                   const py::object& gradation, const py::object& hmin, const py::object& hmax,
                                   const py::object& max_anisotropy) {
  const Mesh& mesh = m.mesh();
  const MultiscaleOptions o =
      multiscale_options("hessian_metric", complexity, norm, gradation, hmin, hmax, max_anisotropy);
  // Any symmetric tensor: the metric takes the absolute values of its
  // eigenvalues.
  std::vector<Sym6> h = metric_by_id(mesh, hessian, "hessian_metric: hessian", false);
  return metric_array(mesh, multiscale_metric_from_hessian(mesh, std::move(h), o));
}

py::array_t<double> intersect(const py::object& a, const py::object& b) {
  const auto x = float_rows(a, 6, "intersect: first metric");
  const auto y = float_rows(b, 6, "intersect: second metric");
  if (x.shape(0) != y.shape(0))
    throw InputError(fmt::format("intersect: {} tensors against {}", x.shape(0), y.shape(0)));
  const auto n = static_cast<std::size_t>(x.shape(0));
  std::vector<Sym6> p(n), q(n);
  std::memcpy(static_cast<void*>(p.data()), x.data(), sizeof(Sym6) * n);
  std::memcpy(static_cast<void*>(q.data()), y.data(), sizeof(Sym6) * n);
  check_metric_field(p, "intersect: first metric");
  check_metric_field(q, "intersect: second metric");
  py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{6}});
  for (std::size_t i = 0; i < n; ++i) {
    const Sym6 m = metrica::intersect(p[i], q[i]);
    std::memcpy(out.mutable_data() + 6 * i, m.data(), sizeof(Sym6));
  }
  return out;
}

double complexity(const PyMesh& m, const py::object& metric) {
  return metrica::complexity(m.mesh(), metric_by_id(m.mesh(), metric));
}

py::array_t<double> interpolate(const PyMesh& from, const py::object& field, const PyMesh& to, bool metric) {
  if (metric) {
    // Log-Euclidean: the tensors' logarithms moved, then exponentiated.
    const BackgroundMetric moved(from.mesh(), metric_by_id(from.mesh(), field, "field"));
    Mesh target = to.mesh();
    moved.assign(target);
    std::vector<Sym6> by_id(target.vertex_capacity(), isotropic_metric(1.0));
    for (VertexId v = 0; v < target.vertex_capacity(); ++v)
      if (target.vertex_alive(v)) by_id[v] = target.metric(v);
    return metric_array(target, by_id);
  }
  const std::size_t width = width_of(field, "field");
  const std::vector<double> values = values_by_id(from.mesh(), field, width, "field");
  const std::vector<double> out =
      width == 0 ? interpolate_vertex_field(from.mesh(), values, to.mesh())
                 : interpolate_vertex_values(from.mesh(), values, static_cast<int>(width), to.mesh());
  return values_array(to.mesh(), out, width);
}

namespace {

// `exact` as a function of many points: an analytic field's name, or a
// Python callable taking a (k, 3) array of points and returning k values.
PointsFunction exact_field(const py::object& exact) {
  if (py::isinstance<py::str>(exact)) {
    const AnalyticField kind = analytic_field_from_name(exact.cast<std::string>());
    return [kind](const std::vector<Point>& points) {
      std::vector<double> out(points.size());
      for (std::size_t i = 0; i < points.size(); ++i) out[i] = evaluate(kind, points[i]);
      return out;
    };
  }
  if (!PyCallable_Check(exact.ptr()))
    throw InputError(
        fmt::format("error: exact is an analytic field's name or a function of a (k, 3) array of "
                    "points (got {})",
                    py::repr(exact).cast<std::string>()));
  return [exact](const std::vector<Point>& points) {
    const auto k = static_cast<py::ssize_t>(points.size());
    py::array_t<double> xyz({k, py::ssize_t{3}});
    for (py::ssize_t i = 0; i < k; ++i)
      for (int c = 0; c < 3; ++c) xyz.mutable_at(i, c) = points[static_cast<std::size_t>(i)][c];
    const auto values = py::array::ensure(exact(xyz));
    if (!values || values.ndim() != 1 || values.shape(0) != k ||
        (values.dtype().kind() != 'f' && values.dtype().kind() != 'i'))
      throw InputError(fmt::format("error: exact(points) must return {} numbers, shape ({},)", k, k));
    const auto u = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
    return std::vector<double>(u.data(), u.data() + k);
  };
}

}  // namespace

double l2_error(const PyMesh& m, const py::object& values, const py::object& exact, const py::object& reference,
                const py::object& reference_values) {
  const std::vector<double> u = values_by_id(m.mesh(), values, 0, "values");
  double error = 0.0;
  if (!reference.is_none()) {
    const PyMesh& truth = reference.cast<const PyMesh&>();
    std::vector<double> v;
    if (!reference_values.is_none()) {
      v = values_by_id(truth.mesh(), reference_values, 0, "reference_values");
    } else if (!exact.is_none()) {
      const Mesh& t = truth.mesh();
      const std::vector<Point> points = vertex_points(t);
      v = exact_field(exact)(points);
      for (VertexId i = 0; i < t.vertex_capacity(); ++i)
        if (!t.vertex_alive(i)) v[i] = 0.0;
    } else {
      throw InputError("error: give the reference mesh's values (reference_values) or an analytic field (exact)");
    }
    error = l2_difference(truth.mesh(), interpolate_vertex_field(m.mesh(), u, truth.mesh()), v);
  } else {
    if (exact.is_none()) throw InputError("error: give an analytic field (exact) or a reference mesh");
    if (py::isinstance<py::str>(exact)) {
      const AnalyticField kind = analytic_field_from_name(exact.cast<std::string>());
      error = l2_interpolation_error(m.mesh(), u, [kind](const Point& p) { return evaluate(kind, p); });
    } else {
      error = l2_interpolation_error_in_bulk(m.mesh(), u, exact_field(exact));
    }
  }
  if (!std::isfinite(error)) throw InputError("error: the L2 error is not finite");
  return error;
}

}  // namespace metrica::python
