#include <metrica/error.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <vector>

namespace metrica {

namespace {

std::vector<Sym6> logarithms(const Mesh& mesh, std::span<const Sym6> metric) {
  if (metric.size() != mesh.vertex_capacity())
    throw InputError(fmt::format("background metric: {} tensors for a mesh of {} vertex ids", metric.size(),
                                 mesh.vertex_capacity()));
  std::vector<Sym6> log_m(metric.size(), Sym6{});
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    if (!is_spd(metric[v]))
      throw InputError(
          fmt::format("background metric: the tensor at vertex {} is not symmetric positive definite", numbered(v)));
    log_m[v] = spd_log(metric[v]);
  }
  return log_m;
}

std::vector<Sym6> own_logarithms(const Mesh& mesh) {
  if (!mesh.has_metric()) throw InputError("background metric: the mesh has no metric");
  std::vector<Sym6> log_m(mesh.vertex_capacity(), Sym6{});
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_alive(v)) log_m[v] = mesh.log_metric(v);
  return log_m;
}

}  // namespace

BackgroundMetric::BackgroundMetric(const Mesh& mesh, std::span<const Sym6> metric)
    : mesh_(mesh.location_copy()), log_metric_(logarithms(mesh, metric)), locator_(mesh_) {}

BackgroundMetric::BackgroundMetric(const Mesh& mesh)
    : mesh_(mesh.location_copy()), log_metric_(own_logarithms(mesh)), locator_(mesh_) {}

BackgroundMetric::Sample BackgroundMetric::at(const Point& p, TetId start) const {
  const Location loc = locator_.locate(p, start);
  const auto& tv = mesh_.tet(loc.tet);
  Sym6 l{};
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 6; ++c) l[c] += loc.bary[k] * log_metric_[tv[k]][c];
  return {{spd_exp(l), l, loc.tet}, loc.inside};
}

void BackgroundMetric::attach(Mesh& mesh) const {
  mesh.enable_background_tets();
  TetId previous = kNoId;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    const bool same = v < mesh_.vertex_capacity() && mesh_.vertex_alive(v) && mesh_.point(v) == mesh.point(v) &&
                      mesh_.vert2tet(v) != kNoId;
    const TetId t = same ? mesh_.vert2tet(v) : locator_.locate(mesh.point(v), previous).tet;
    mesh.set_background_tet(v, t);
    previous = t;
  }
}

std::size_t BackgroundMetric::assign(Mesh& mesh, const PartRunner& run) const {
  mesh.enable_background_tets();
  // Each vertex writes only its own entries (the walks read the
  // background), once the mesh has its metric's attribute: the first
  // set_metric adds it, alone.
  const std::size_t parts = mesh.has_metric() ? std::max<std::size_t>(run.parts, 1) : 1, n = mesh.vertex_capacity();
  struct alignas(64) Outside {
    std::size_t count = 0;
  };
  std::vector<Outside> outside(parts);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(n, parts, p);
    TetId previous = kNoId;
    for (std::size_t i = first; i < last; ++i) {
      const auto v = static_cast<VertexId>(i);
      if (!mesh.vertex_alive(v)) continue;
      const TetId own = mesh.background_tet(v);
      const Sample s = at(mesh.point(v), own != kNoId ? own : previous);
      set_vertex_metric(mesh, v, s.metric);
      previous = s.metric.background;
      outside[p].count += !s.inside;
    }
  });
  mesh.clear_quality_cache();
  std::size_t all = 0;
  for (const auto& o : outside) all += o.count;
  return all;
}

}  // namespace metrica
