#include <metrica/error.hpp>
#include <metrica/metrics/background_metric.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

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

std::size_t BackgroundMetric::assign(Mesh& mesh) const {
  mesh.enable_background_tets();
  std::size_t outside = 0;
  TetId previous = kNoId;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    const TetId own = mesh.background_tet(v);
    const Sample s = at(mesh.point(v), own != kNoId ? own : previous);
    set_vertex_metric(mesh, v, s.metric);
    previous = s.metric.background;
    outside += !s.inside;
  }
  mesh.clear_quality_cache();
  return outside;
}

}  // namespace metrica
