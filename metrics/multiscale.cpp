#include <metrica/error.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/intersection.hpp>
#include <metrica/metrics/multiscale.hpp>
#include <metrica/metrics/recovery.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <optional>

namespace metrica {

namespace {

// Eigenvalues below this share of the field's largest are raised to it, so
// that det|H| > 0 where the field is locally linear; h_max then decides.
constexpr double kRelativeEigenFloor = 1e-12;

void check_options(const MultiscaleOptions& o) {
  if (!(o.complexity > 0.0) || !std::isfinite(o.complexity))
    throw InputError(fmt::format("the target complexity must be a positive number (got {})", o.complexity));
  if (!(o.norm >= 1.0) || !std::isfinite(o.norm))
    throw InputError(fmt::format("the norm p must be a number >= 1 (got {})", o.norm));
  check_bounds(o.bounds);
  if (o.gradation && !(o.gradation_options.beta >= 1.0))
    throw InputError(fmt::format("the gradation must be >= 1 (got {})", o.gradation_options.beta));
}

// M_i = det|H_i|^(-1/(2p+3)) |H_i| (before the constant D_N), with the
// determinant the product of the eigenvalues (a rotated Hessian of rank one
// or two, a planar or cylindrical front, cancels in its entries). The
// anisotropy bound does not depend on the scale, so it acts here, before
// the first scaling; the size bounds act after it.
std::vector<Sym6> unscaled_metric(const Mesh& mesh, const std::vector<Sym6>& hessian, double norm,
                                  double max_anisotropy) {
  std::vector<Eigen3> eig(hessian.size());
  double largest = 0.0;
  for (std::size_t v = 0; v < hessian.size(); ++v) {
    if (!mesh.vertex_alive(static_cast<VertexId>(v))) continue;
    eig[v] = eigen_decomposition(hessian[v]);
    eig[v].values = eig[v].values.cwiseAbs();
    largest = std::max(largest, eig[v].values.maxCoeff());
  }
  if (!(largest > 0.0) || !std::isfinite(largest))
    throw InputError("the field's Hessian is zero everywhere (a linear field): no multiscale metric to make");
  const double floor = kRelativeEigenFloor * largest;
  const double exponent = -1.0 / (2.0 * norm + 3.0);
  std::vector<Sym6> metric(hessian.size(), isotropic_metric(1.0));
  for (std::size_t v = 0; v < hessian.size(); ++v) {
    if (!mesh.vertex_alive(static_cast<VertexId>(v))) continue;
    Eigen::Vector3d l = eig[v].values.cwiseMax(floor);
    l = l.cwiseMax(l.maxCoeff() / (max_anisotropy * max_anisotropy));
    l *= std::pow(l.prod(), exponent);
    metric[v] = to_sym6(eig[v].vectors * l.asDiagonal() * eig[v].vectors.transpose());
  }
  return metric;
}

// The recovered Hessian of a vertex field, or nothing when it is at
// round-off level of the gradient's scale (the field is linear and asks for
// no particular size).
std::optional<std::vector<Sym6>> field_hessian(const Mesh& mesh, const std::vector<double>& values,
                                               const MultiscaleOptions& o) {
  const auto gradient = recover_gradient(mesh, values);
  auto hessian = recover_hessian(mesh, gradient);
  if (o.extrapolate_boundary) extrapolate_hessian_to_boundary(mesh, hessian);
  double gmax = 0.0, hmax = 0.0;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    gmax = std::max(gmax, gradient[v].norm());
    hmax = std::max(hmax, to_matrix(hessian[v]).norm());
  }
  const auto box = bounding_box(mesh);
  if (!(hmax > 1e-9 * gmax / (box.hi - box.lo).norm())) return std::nullopt;
  return hessian;
}

// Scale to N, then bounds and gradation with rescaling until the
// complexity is back at N (at most max_relaxations rounds).
void relax_to_complexity(const Mesh& mesh, std::vector<Sym6>& metric, const MultiscaleOptions& o, MultiscaleReport& r) {
  // Sizes beyond the domain mean nothing a mesh could follow; bounding them
  // by its largest extent (unless the user set h_max) also spares the
  // gradation from walking down sizes of 1e6 in flat regions.
  MetricBounds bounds = o.bounds;
  if (!(bounds.hmax < std::numeric_limits<double>::infinity())) {
    const auto box = bounding_box(mesh);
    bounds.hmax = std::max((box.hi - box.lo).maxCoeff(), bounds.hmin);
  }
  const auto dual = dual_volumes(mesh);
  scale_to_complexity(metric, dual, o.complexity);
  const bool relax = bounds.active() || o.gradation;
  for (r.relaxations = 0; relax && r.relaxations < o.max_relaxations;) {
    ++r.relaxations;
    clamp_metrics(metric, bounds);
    if (o.gradation) {
      Stopwatch g;
      limit_gradation(mesh, metric, o.gradation_options);
      r.gradation_seconds += g.seconds();
    }
    const double c = complexity(metric, dual);
    if (std::abs(c / o.complexity - 1.0) < o.complexity_tolerance) break;
    scale_to_complexity(metric, dual, o.complexity);
  }
  r.complexity = complexity(metric, dual);
}

}  // namespace

std::vector<Sym6> multiscale_metric_from_hessian(const Mesh& mesh, std::vector<Sym6> hessian,
                                                 const MultiscaleOptions& o, MultiscaleReport* report) {
  check_options(o);
  Stopwatch clock;
  if (hessian.size() != mesh.vertex_capacity())
    throw InputError(
        fmt::format("Hessian field of {} tensors for {} vertex ids", hessian.size(), mesh.vertex_capacity()));
  auto metric = unscaled_metric(mesh, hessian, o.norm, o.bounds.max_anisotropy);
  MultiscaleReport r;
  relax_to_complexity(mesh, metric, o, r);
  r.total_seconds = clock.seconds();
  if (report) *report = r;
  return metric;
}

std::vector<Sym6> multiscale_metric(const Mesh& mesh, const std::vector<double>& values, const MultiscaleOptions& o,
                                    MultiscaleReport* report) {
  check_options(o);
  Stopwatch clock;
  auto hessian = field_hessian(mesh, values, o);
  if (!hessian)
    throw InputError("the field's Hessian is zero everywhere (a linear field): no multiscale metric to make");
  const double hessian_seconds = clock.seconds();
  MultiscaleReport r;
  auto metric = multiscale_metric_from_hessian(mesh, std::move(*hessian), o, &r);
  r.hessian_seconds = hessian_seconds;
  r.total_seconds += hessian_seconds;
  if (report) *report = r;
  return metric;
}

std::vector<Sym6> multiscale_metric(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                                    const MultiscaleOptions& o, MultiscaleReport* report) {
  check_options(o);
  if (fields.empty()) throw InputError("no field to make a multiscale metric of");
  Stopwatch clock;
  const auto dual = dual_volumes(mesh);
  std::vector<Sym6> metric;
  std::size_t used = 0;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const auto hessian = field_hessian(mesh, fields[k], o);
    if (!hessian) {
      log::warn("multiscale: field {} of {} has a zero Hessian (linear or constant): left out", k + 1, fields.size());
      continue;
    }
    auto mk = unscaled_metric(mesh, *hessian, o.norm, o.bounds.max_anisotropy);
    scale_to_complexity(mk, dual, o.complexity);
    if (used++ == 0) {
      metric = std::move(mk);
    } else {
      for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
        if (mesh.vertex_alive(v)) metric[v] = intersect(metric[v], mk[v]);
    }
  }
  if (used == 0)
    throw InputError("every field's Hessian is zero everywhere (linear fields): no multiscale metric to make");
  MultiscaleReport r;
  r.hessian_seconds = clock.seconds();
  relax_to_complexity(mesh, metric, o, r);
  r.total_seconds = clock.seconds();
  if (report) *report = r;
  return metric;
}

}  // namespace metrica
