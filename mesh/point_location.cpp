#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/point_location.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace metrica {
namespace {

// Barycentric coordinates of p in tet t (signed volumes over the volume).
std::array<double, 4> barycentric(const Mesh& mesh, TetId t, const Point& p) {
  const auto& v = mesh.tet(t);
  const Point a = mesh.point(v[0]), b = mesh.point(v[1]), c = mesh.point(v[2]), d = mesh.point(v[3]);
  const double vol = tet_volume(a, b, c, d);
  return {tet_volume(p, b, c, d) / vol, tet_volume(a, p, c, d) / vol, tet_volume(a, b, p, d) / vol,
          tet_volume(a, b, c, p) / vol};
}

std::array<double, 4> clamped(std::array<double, 4> l) {
  double sum = 0;
  for (double& x : l) sum += (x = std::max(x, 0.0));
  for (double& x : l) x /= sum;
  return l;
}

}  // namespace

Location locate(const Mesh& mesh, const Point& p, TetId start) {
  Location out;
  TetId t = start;
  if (t == kNoId || t >= mesh.tet_capacity() || !mesh.tet_alive(t)) {
    t = 0;
    while (t < mesh.tet_capacity() && !mesh.tet_alive(t)) ++t;
    if (t == mesh.tet_capacity()) throw InputError("point location in a mesh without tets");
  }
  constexpr double kTolerance = -1e-12;
  TetId best = t;
  double best_min = -std::numeric_limits<double>::infinity();
  std::array<double, 4> best_bary{};
  const std::size_t max_steps = 4 * mesh.num_tets() + 16;
  TetId previous = kNoId;
  for (std::size_t step = 0; step < max_steps; ++step) {
    const auto l = barycentric(mesh, t, p);
    int worst = 0;
    for (int k = 1; k < 4; ++k)
      if (l[k] < l[worst]) worst = k;
    if (l[worst] > best_min) {
      best_min = l[worst];
      best = t;
      best_bary = l;
    }
    out.steps = static_cast<int>(step);
    if (l[worst] >= kTolerance) {
      out.tet = t;
      out.bary = clamped(l);
      out.inside = true;
      return out;
    }
    // Across the most negative face; when that leads back or out, the next
    // most negative one that leads on (breaks the rare cycles of a
    // visibility walk on anisotropic meshes).
    std::array<int, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](int x, int y) { return l[x] < l[y]; });
    TetId next = kNoId;
    for (int k : order) {
      if (l[k] >= kTolerance) break;
      const FaceRef n = mesh.neighbour(t, k);
      if (n.valid() && n.tet() != previous) {
        next = n.tet();
        break;
      }
    }
    if (next == kNoId) break;  // outside, behind a boundary face
    previous = t;
    t = next;
  }
  // Outside the mesh (or a walk that did not end): the best tet seen,
  // coordinates clamped.
  out.tet = best;
  out.bary = clamped(best_bary);
  out.inside = false;
  return out;
}

std::vector<double> interpolate_vertex_values(const Mesh& from, const std::vector<double>& values, int width,
                                              const Mesh& to, std::size_t* outside) {
  if (width < 1) throw InputError(fmt::format("interpolate: {} values per vertex", width));
  const auto w = static_cast<std::size_t>(width);
  if (values.size() != from.vertex_capacity() * w)
    throw InputError(fmt::format("interpolate: {} values for a mesh of {} vertex ids ({} per vertex)", values.size(),
                                 from.vertex_capacity(), width));
  std::vector<double> out(to.vertex_capacity() * w, 0.0);
  std::size_t n_outside = 0;
  TetId hint = kNoId;
  for (VertexId v = 0; v < to.vertex_capacity(); ++v) {
    if (!to.vertex_alive(v)) continue;
    const Location loc = locate(from, to.point(v), hint);
    hint = loc.tet;
    n_outside += !loc.inside;
    const auto& tv = from.tet(loc.tet);
    for (std::size_t c = 0; c < w; ++c) {
      double x = 0;
      for (int k = 0; k < 4; ++k) x += loc.bary[k] * values[tv[k] * w + c];
      out[v * w + c] = x;
    }
  }
  if (outside != nullptr) *outside = n_outside;
  return out;
}

std::vector<double> interpolate_vertex_field(const Mesh& from, const std::vector<double>& values, const Mesh& to,
                                             std::size_t* outside) {
  return interpolate_vertex_values(from, values, 1, to, outside);
}

}  // namespace metrica
