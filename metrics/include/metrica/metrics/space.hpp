// The Space policy: how geometry is measured (docs/architecture.md, "The three
// policies"). A Space is a stateless class whose static functions read the
// points and per-vertex metrics of a Mesh; operators are templates over it.
//
//   Isotropic     one size per vertex, h = det(M)^(-1/6) (the isotropic
//                 metric of the same volume), interpolated linearly in h;
//   Anisotropic   the tensors, interpolated linearly: sum a_i M_i;
//   LogEuclidean  the tensors, interpolated as exp(sum a_i log M_i) (seed,
//                 eq. (metric_interpolation); Arsigny et al. 2006), with
//                 log M_i stored beside M_i so no log is taken on the way.
//
// All three use the UGAWG edge length and the mean ratio with the metric
// interpolated at the centroid, so a report means the same for each.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/metrics/measures.hpp>
#include <metrica/policy_list.hpp>

#include <cassert>
#include <concepts>
#include <span>
#include <string_view>

namespace metrica {

// A metric to store at a (new) vertex: M and log M, and the background
// tet it was sampled in (background_metric.hpp; kNoId: not sampled).
struct VertexMetric {
  Sym6 m{}, log_m{};
  TetId background = kNoId;
};

// Stores m at v (and its background tet, when the mesh keeps them).
inline void set_vertex_metric(Mesh& mesh, VertexId v, const VertexMetric& m) {
  mesh.set_metric(v, m.m, m.log_m);
  if (m.background != kNoId) mesh.set_background_tet(v, m.background);
}

template <class S>
concept MetricSpace = requires(const Mesh& mesh, VertexId a, const TetVertices& t, const TetPoints& p,
                               std::span<const VertexId> ids, std::span<const double> w, const Sym6& m,
                               const VertexMetric& vm) {
  { S::name } -> std::convertible_to<std::string_view>;
  // The tensor the space sees at a vertex (Isotropic: the isotropic
  // metric of the same volume).
  { S::vertex_metric(mesh, a) } -> std::convertible_to<Sym6>;
  // The metric at the barycentric point sum w_i x_{ids_i} (sum w_i = 1),
  // alone, and with its logarithm (to store at a new vertex).
  { S::metric_at(mesh, ids, w) } -> std::same_as<Sym6>;
  { S::interpolate(mesh, ids, w) } -> std::same_as<VertexMetric>;
  // The metric of a tet: interpolated at its centroid; and the same were
  // its vertex a to take the metric vm (a move's preview, the metric
  // sampled at the new position).
  { S::tet_metric(mesh, t) } -> std::same_as<Sym6>;
  { S::tet_metric_with(mesh, t, a, vm) } -> std::same_as<Sym6>;
  { S::edge_length(mesh, a, a) } -> std::same_as<double>;
  // Is edge_length in the band (most edges decided without the length)?
  { S::edge_length_in(mesh, a, a, kUnitBand) } -> std::same_as<bool>;
  // Mean ratio and metric volume of tet t, at the mesh's points or with
  // the vertices at the points p (a trial position, e.g. in smoothing).
  { S::mean_ratio(mesh, t) } -> std::same_as<double>;
  { S::mean_ratio(mesh, t, p) } -> std::same_as<double>;
  // The cube of mean_ratio without its cube root (for comparisons).
  { S::mean_ratio_cubed(mesh, t) } -> std::same_as<double>;
  { S::metric_volume(mesh, t) } -> std::same_as<double>;
  // L with M = L^T L, mapping vectors into the metric's Euclidean space;
  // upper triangular (M's Cholesky factor), so L^-1 is a back substitution.
  { S::factor(m) } -> std::same_as<Matrix3>;
};

namespace detail {
inline TetPoints tet_points(const Mesh& mesh, const TetVertices& t) {
  return {mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2]), mesh.point(t[3])};
}
inline constexpr std::array<double, 4> kCentroidWeights{0.25, 0.25, 0.25, 0.25};
}  // namespace detail

// The points of tet t with its vertex v at p: a tet of a moved or merged
// vertex's ball, as a trial sees it.
inline TetPoints tet_points_moved(const Mesh& mesh, const TetVertices& t, VertexId v, const Point& p) {
  TetPoints x = detail::tet_points(mesh, t);
  x[local_index(t, v)] = p;
  return x;
}

namespace detail {

// The parts shared by every space, given Derived::vertex_metric (the
// tensor a space sees at a vertex) and Derived::metric_at.
template <class Derived>
struct SpaceCommon {
  static double edge_length(const Mesh& mesh, VertexId a, VertexId b) {
    return ugawg_length(mesh.point(b) - mesh.point(a), Derived::vertex_metric(mesh, a),
                        Derived::vertex_metric(mesh, b));
  }
  static bool edge_length_in(const Mesh& mesh, VertexId a, VertexId b, const UnitBand& band) {
    return ugawg_length_in(band, mesh.point(b) - mesh.point(a), Derived::vertex_metric(mesh, a),
                           Derived::vertex_metric(mesh, b));
  }
  static Sym6 tet_metric(const Mesh& mesh, const TetVertices& t) {
    return Derived::metric_at(mesh, std::span<const VertexId>(t), kCentroidWeights);
  }
  static double mean_ratio(const Mesh& mesh, const TetVertices& t, const TetPoints& p) {
    return metrica::mean_ratio(p, tet_metric(mesh, t));
  }
  static double mean_ratio(const Mesh& mesh, const TetVertices& t) {
    return metrica::mean_ratio(tet_points(mesh, t), tet_metric(mesh, t));
  }
  static double mean_ratio_cubed(const Mesh& mesh, const TetVertices& t) {
    return metrica::mean_ratio_cubed(tet_points(mesh, t), tet_metric(mesh, t));
  }
  static double metric_volume(const Mesh& mesh, const TetVertices& t) {
    return metrica::metric_volume(tet_points(mesh, t), tet_metric(mesh, t));
  }
  static Matrix3 factor(const Sym6& m) { return metric_factor(m); }
};
}  // namespace detail

struct Isotropic : detail::SpaceCommon<Isotropic> {
  static constexpr std::string_view name = "isotropic";
  static double size(const Sym6& m) { return 1.0 / std::sqrt(std::cbrt(spd_determinant(m))); }
  static Sym6 vertex_metric(const Mesh& mesh, VertexId v) { return isotropic_metric(size(mesh.metric(v))); }
  static Sym6 metric_at(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    double h = 0.0;
    for (std::size_t i = 0; i < ids.size(); ++i) h += w[i] * size(mesh.metric(ids[i]));
    return isotropic_metric(h);
  }
  static Sym6 tet_metric_with(const Mesh& mesh, const TetVertices& t, VertexId v, const VertexMetric& vm) {
    double h = 0.0;
    for (VertexId u : t) h += 0.25 * size(u == v ? vm.m : mesh.metric(u));
    return isotropic_metric(h);
  }
  static VertexMetric interpolate(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    const Sym6 m = metric_at(mesh, ids, w);
    const double l = std::log(m[0]);
    return {m, {l, 0, l, 0, 0, l}};
  }
  // The isotropic metric is a multiple of I: its factor is diagonal.
  static Matrix3 factor(const Sym6& m) { return std::sqrt(m[0]) * Matrix3::Identity(); }
};

struct Anisotropic : detail::SpaceCommon<Anisotropic> {
  static constexpr std::string_view name = "anisotropic";
  static const Sym6& vertex_metric(const Mesh& mesh, VertexId v) { return mesh.metric(v); }
  static Sym6 metric_at(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    Sym6 m{};
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (int c = 0; c < 6; ++c) m[c] += w[i] * mesh.metric(ids[i])[c];
    return m;
  }
  static Sym6 tet_metric_with(const Mesh& mesh, const TetVertices& t, VertexId v, const VertexMetric& vm) {
    Sym6 m{};
    for (VertexId u : t) {
      const Sym6& mu = u == v ? vm.m : mesh.metric(u);
      for (int c = 0; c < 6; ++c) m[c] += 0.25 * mu[c];
    }
    return m;
  }
  static VertexMetric interpolate(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    const Sym6 m = metric_at(mesh, ids, w);
    return {m, spd_log(m)};
  }
};

struct LogEuclidean : detail::SpaceCommon<LogEuclidean> {
  static constexpr std::string_view name = "log-euclidean";
  static const Sym6& vertex_metric(const Mesh& mesh, VertexId v) { return mesh.metric(v); }
  static VertexMetric interpolate(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    Sym6 l{};
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (int c = 0; c < 6; ++c) l[c] += w[i] * mesh.log_metric(ids[i])[c];
    return {spd_exp(l), l};
  }
  // For measuring only: the fast exponential (the stored metric of a new
  // vertex comes from interpolate).
  static Sym6 metric_at(const Mesh& mesh, std::span<const VertexId> ids, std::span<const double> w) {
    Sym6 l{};
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (int c = 0; c < 6; ++c) l[c] += w[i] * mesh.log_metric(ids[i])[c];
    return spd_exp_fast(l);
  }
  static Sym6 tet_metric_with(const Mesh& mesh, const TetVertices& t, VertexId v, const VertexMetric& vm) {
    Sym6 l{};
    for (VertexId u : t) {
      const Sym6& lu = u == v ? vm.log_m : mesh.log_metric(u);
      for (int c = 0; c < 6; ++c) l[c] += 0.25 * lu[c];
    }
    return spd_exp_fast(l);
  }
};

// The mean ratio of live tet t in space S through the mesh's quality
// cache (Mesh::cached_quality): computed once per version of the tet.
// Valid while one Space measures the mesh: the Adapter clears the cache
// and names its Space (Mesh::clear_quality_cache), which debug builds
// check here.
template <MetricSpace S>
double cached_mean_ratio(const Mesh& mesh, TetId t) {
  assert(mesh.quality_cache_space().empty() || mesh.quality_cache_space() == S::name);
  double q = mesh.cached_quality(t);
  if (q == Mesh::kUnknownQuality) {
    q = S::mean_ratio(mesh, mesh.tet(t));
    mesh.cache_quality(t, q);
  }
  return q;
}

static_assert(MetricSpace<Isotropic>);
static_assert(MetricSpace<Anisotropic>);
static_assert(MetricSpace<LogEuclidean>);

// The spaces offered by name (--space), the default first.
using Spaces = PolicyList<LogEuclidean, Anisotropic, Isotropic>;

}  // namespace metrica
