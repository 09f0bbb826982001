#include <metrica/error.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/numbering.hpp>
#include <metrica/point_location.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace metrica {

namespace {

// Each tensor's eigenvalues (ascending), once every tensor is known to be
// finite and positive definite: the first bad one is an InputError.
std::vector<Eigen::Vector3d> checked_eigenvalues(const std::vector<Sym6>& metrics, const std::string& source) {
  std::vector<Eigen::Vector3d> values(metrics.size());
  for (std::size_t v = 0; v < metrics.size(); ++v) {
    const auto& m = metrics[v];
    for (double x : m)
      if (!std::isfinite(x))
        throw InputError(fmt::format("{}: metric at vertex {} has a non-finite entry ({})", source, numbered(v), x));
    const auto e = eigen_decomposition(m);
    if (!(e.values[0] > 0.0))
      throw InputError(
          fmt::format("{}: metric at vertex {} is not positive definite (eigenvalues {:.3g} {:.3g} {:.3g})", source,
                      numbered(v), e.values[0], e.values[1], e.values[2]));
    values[v] = e.values;
  }
  return values;
}

}  // namespace

void check_metric_entries(const std::vector<Sym6>& metrics, const std::string& source) {
  static_cast<void>(checked_eigenvalues(metrics, source));
}

void check_metric_field(const std::vector<Sym6>& metrics, const std::string& source) {
  const auto values = checked_eigenvalues(metrics, source);
  const double lo = 1.0 / (kLargestSize * kLargestSize), hi = 1.0 / (kSmallestSize * kSmallestSize);
  for (std::size_t v = 0; v < metrics.size(); ++v) {
    const auto& l = values[v];
    if (!(l[0] >= lo && l[2] <= hi))
      throw InputError(
          fmt::format("{}: metric at vertex {} asks for sizes {:.3g} to {:.3g}, outside [{:g}, {:g}] "
                      "(bound them with --hmin/--hmax)",
                      source, numbered(v), 1.0 / std::sqrt(l[2]), 1.0 / std::sqrt(l[0]), kSmallestSize, kLargestSize));
  }
}

std::vector<Sym6> metric_field_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source) {
  if (sol.count != vertices)
    throw InputError(
        fmt::format("{}: the metric has {} entries but the mesh has {} vertices", source, sol.count, vertices));
  std::vector<Sym6> out(vertices);
  const auto stride = static_cast<std::size_t>(sol.stride());
  for (std::size_t k = 0; k < sol.types.size(); ++k) {
    const auto off = static_cast<std::size_t>(sol.offset(k));
    if (sol.types[k] == io::SolType::sym_matrix) {
      for (std::size_t v = 0; v < vertices; ++v)
        for (int c = 0; c < 6; ++c) out[v][c] = sol.values[v * stride + off + c];
    } else if (sol.types[k] == io::SolType::scalar) {
      for (std::size_t v = 0; v < vertices; ++v) {
        const double h = sol.values[v * stride + off];
        if (!(h > 0.0) || !std::isfinite(h))
          throw InputError(fmt::format("{}: size at vertex {} is {} (must be finite and > 0)", source, numbered(v), h));
        out[v] = isotropic_metric(h);
      }
    } else {
      continue;
    }
    check_metric_entries(out, source);
    return out;
  }
  throw InputError(fmt::format("{}: no scalar or symmetric-matrix field to use as a metric", source));
}

std::vector<double> scalar_field_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source) {
  if (sol.count != vertices)
    throw InputError(
        fmt::format("{}: the field has {} entries but the mesh has {} vertices", source, sol.count, vertices));
  for (std::size_t k = 0; k < sol.types.size(); ++k) {
    if (sol.types[k] != io::SolType::scalar) continue;
    std::vector<double> out = sol.field(k);
    for (std::size_t v = 0; v < out.size(); ++v)
      if (!std::isfinite(out[v]))
        throw InputError(fmt::format("{}: value at vertex {} is not finite ({})", source, numbered(v), out[v]));
    return out;
  }
  throw InputError(fmt::format("{}: no scalar field in the file", source));
}

namespace {

void check_count(const io::SolData& sol, std::size_t vertices, const std::string& source) {
  if (sol.count != vertices)
    throw InputError(
        fmt::format("{}: the field has {} entries but the mesh has {} vertices", source, sol.count, vertices));
}

void check_finite_values(const std::vector<double>& values, int width, const std::string& source) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw InputError(fmt::format("{}: value at vertex {} is not finite ({})", source,
                                   numbered(i / static_cast<std::size_t>(width)), values[i]));
}

// Component c of field k, contiguous.
std::vector<double> component(const io::SolData& sol, std::size_t k, int c) {
  const auto stride = static_cast<std::size_t>(sol.stride());
  const auto at = static_cast<std::size_t>(sol.offset(k) + c);
  std::vector<double> out(sol.count);
  for (std::size_t v = 0; v < sol.count; ++v) out[v] = sol.values[v * stride + at];
  return out;
}

}  // namespace

std::vector<double> solution_values_from_sol(const io::SolData& sol, std::size_t vertices, const std::string& source) {
  check_count(sol, vertices, source);
  for (std::size_t k = 0; k < sol.types.size(); ++k)
    if (sol.types[k] == io::SolType::matrix)
      throw InputError(
          fmt::format("{}: field {} is a {} (scalar, vector and symmetric matrix fields are solutions to transfer)",
                      source, k + 1, io::to_string(sol.types[k])));
  check_finite_values(sol.values, sol.stride(), source);
  const auto stride = static_cast<std::size_t>(sol.stride());
  for (std::size_t k = 0; k < sol.types.size(); ++k) {
    if (sol.types[k] != io::SolType::sym_matrix) continue;
    const auto at = static_cast<std::size_t>(sol.offset(k));
    for (std::size_t v = 0; v < sol.count; ++v) {
      Sym6 m;
      std::copy_n(sol.values.begin() + static_cast<std::ptrdiff_t>(v * stride + at), 6, m.begin());
      if (!is_spd(m))
        throw InputError(
            fmt::format("{}: field {} at vertex {} is not symmetric positive definite", source, k + 1, numbered(v)));
    }
  }
  return sol.values;
}

io::SolData transfer_solution(const Mesh& from, const io::SolData& sol, const Mesh& to, const std::string& source,
                              std::size_t* outside) {
  std::vector<double> values = solution_values_from_sol(sol, from.vertex_capacity(), source);
  const auto stride = static_cast<std::size_t>(sol.stride());
  // Each tensor field's entry (offset) whose values are taken to and from
  // the log space around the P1 interpolation.
  std::vector<std::size_t> tensors;
  for (std::size_t k = 0; k < sol.types.size(); ++k)
    if (sol.types[k] == io::SolType::sym_matrix) tensors.push_back(static_cast<std::size_t>(sol.offset(k)));
  auto map = [stride, &tensors](std::vector<double>& x, Sym6 (*f)(const Sym6&)) {
    for (std::size_t at : tensors)
      for (std::size_t v = 0; v < x.size() / stride; ++v) {
        const auto first = x.begin() + static_cast<std::ptrdiff_t>(v * stride + at);
        Sym6 m;
        std::copy_n(first, 6, m.begin());
        m = f(m);
        std::copy(m.begin(), m.end(), first);
      }
  };
  map(values, spd_log);
  std::vector<double> out = interpolate_vertex_values(from, values, static_cast<int>(stride), to, outside);
  out.resize(to.vertex_capacity() * stride);
  io::SolData moved;
  moved.types = sol.types;
  moved.count = to.vertex_capacity();
  // A dead vertex of `to` has zeros (its log): exp gives I, never written.
  map(out, spd_exp);
  moved.values = std::move(out);
  return moved;
}

std::vector<FieldItem> parse_field_selection(const std::string& selection) {
  std::vector<FieldItem> out;
  std::size_t from = 0;
  while (from <= selection.size()) {
    const auto to = std::min(selection.find(',', from), selection.size());
    const std::string item = selection.substr(from, to - from);
    from = to + 1;
    if (item == "all") {
      out.push_back({.all = true});
      continue;
    }
    const auto dot = item.find('.');
    const std::string number = item.substr(0, dot), c = dot == std::string::npos ? "" : item.substr(dot + 1);
    const bool digits =
        !number.empty() && number.size() <= 6 && number.find_first_not_of("0123456789") == std::string::npos;
    const int component = dot == std::string::npos ? -1
                          : c == "x" || c == "1"   ? 0
                          : c == "y" || c == "2"   ? 1
                          : c == "z" || c == "3"   ? 2
                                                   : -2;
    if (!digits || component == -2)
      throw InputError(fmt::format("field selection '{}': '{}' is not K, K.x, K.y, K.z or all", selection, item));
    out.push_back({.field = static_cast<std::size_t>(std::stoul(number)), .component = component});
  }
  return out;
}

std::vector<SelectedField> select_fields(const io::SolData& sol, std::size_t vertices, const std::string& selection,
                                         const std::string& source) {
  if (selection.empty()) return {{"first scalar", scalar_field_from_sol(sol, vertices, source)}};
  check_count(sol, vertices, source);
  std::vector<SelectedField> out;
  auto add = [&](std::size_t k, int c) {
    const bool vector = sol.types[k] == io::SolType::vector;
    out.push_back({vector ? fmt::format("{}.{}", k + 1, "xyz"[c]) : fmt::format("{}", k + 1), component(sol, k, c)});
    check_finite_values(out.back().values, 1, fmt::format("{} (field {})", source, out.back().name));
  };
  auto add_field = [&](std::size_t k) {
    if (sol.types[k] == io::SolType::scalar)
      add(k, 0);
    else
      for (int c = 0; c < 3; ++c) add(k, c);
  };
  for (const FieldItem& item : parse_field_selection(selection)) {
    if (item.all) {
      for (std::size_t k = 0; k < sol.types.size(); ++k)
        if (sol.types[k] == io::SolType::scalar || sol.types[k] == io::SolType::vector) add_field(k);
      if (out.empty()) throw InputError(fmt::format("{}: no scalar or vector field in the file", source));
      continue;
    }
    const std::size_t k = item.field;
    if (k < 1 || k > sol.types.size())
      throw InputError(
          fmt::format("field selection '{}': {} holds fields 1 to {}, not {}", selection, source, sol.types.size(), k));
    const auto type = sol.types[k - 1];
    if (type != io::SolType::scalar && type != io::SolType::vector)
      throw InputError(fmt::format("field selection '{}': field {} of {} is a {}, not a scalar or a vector", selection,
                                   k, source, io::to_string(type)));
    if (item.component < 0) {
      add_field(k - 1);
      continue;
    }
    if (type != io::SolType::vector)
      throw InputError(fmt::format("field selection '{}': '{}.{}' names no component (K.x, K.y, K.z of a vector field)",
                                   selection, k, "xyz"[item.component]));
    add(k - 1, item.component);
  }
  return out;
}

io::SolData scalar_field_to_sol(const std::vector<double>& values) {
  io::SolData s;
  s.count = values.size();
  s.types = {io::SolType::scalar};
  s.values = values;
  return s;
}

io::SolData metric_field_to_sol(const std::vector<Sym6>& metrics) {
  io::SolData s;
  s.count = metrics.size();
  s.types = {io::SolType::sym_matrix};
  s.values.reserve(6 * metrics.size());
  for (const auto& m : metrics) s.values.insert(s.values.end(), m.begin(), m.end());
  return s;
}

std::vector<Sym6> analytic_metric_field(AnalyticMetric m, const std::vector<Point>& points) {
  std::vector<Sym6> out(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) out[v] = evaluate(m, points[v]);
  return out;
}

void assign_metric(Mesh& mesh, const std::vector<Sym6>& metrics) {
  if (metrics.size() != mesh.vertex_capacity())
    throw InputError(
        fmt::format("metric field of {} tensors for a mesh of {} vertex ids", metrics.size(), mesh.vertex_capacity()));
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) mesh.set_metric(v, metrics[v], spd_log(metrics[v]));
  mesh.clear_quality_cache();  // every tet's quality changed
}

io::SolData metric_sol(const Mesh& mesh) {
  std::vector<Sym6> live;
  live.reserve(mesh.num_vertices());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) live.push_back(mesh.metric(v));
  return metric_field_to_sol(live);
}

}  // namespace metrica
