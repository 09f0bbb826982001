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

PointLocator::PointLocator(const Mesh& mesh) : mesh_(mesh) {
  const BoundingBox box = bounding_box(mesh);
  const Eigen::Vector3d extent = (box.hi - box.lo).cwiseMax(1e-300);
  round_off_ = 1e-9 * extent.norm();
  // About two tets per cell, cells as cubic as the box allows.
  const double cells = std::max(1.0, static_cast<double>(mesh.num_tets()) / 2.0);
  const double side = std::cbrt(extent.prod() / cells);
  for (int k = 0; k < 3; ++k) n_[k] = std::clamp(static_cast<int>(std::ceil(extent[k] / side)), 1, 1024);
  lo_ = box.lo;
  for (int k = 0; k < 3; ++k) cell_[k] = extent[k] / n_[k];
  cells_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], kNoId);
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    const Point c = 0.25 * (mesh.point(v[0]) + mesh.point(v[1]) + mesh.point(v[2]) + mesh.point(v[3]));
    std::array<int, 3> i{};
    for (int k = 0; k < 3; ++k) i[k] = std::clamp(static_cast<int>((c[k] - lo_[k]) / cell_[k]), 0, n_[k] - 1);
    cells_[(static_cast<std::size_t>(i[2]) * n_[1] + i[1]) * n_[0] + i[0]] = t;
  }
}

void PointLocator::grid_tets(const Point& p, std::vector<TetId>& out) const {
  out.clear();
  std::array<int, 3> c{};
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<int>((p[k] - lo_[k]) / cell_[k]), 0, n_[k] - 1);
  // The tets of the cell of p and of the cells around it (a walk from one
  // of them reaches p around a hole the others meet), else of the nearest
  // shell of cells with a tet (a few shells: beyond, the scan takes over).
  const int most = std::min(std::max({n_[0], n_[1], n_[2]}), 16);
  for (int r = 0; r < most && (r <= 1 || out.empty()); ++r)
    for (int z = std::max(0, c[2] - r); z <= std::min(n_[2] - 1, c[2] + r); ++z)
      for (int y = std::max(0, c[1] - r); y <= std::min(n_[1] - 1, c[1] + r); ++y)
        for (int x = std::max(0, c[0] - r); x <= std::min(n_[0] - 1, c[0] + r); ++x) {
          if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;
          const TetId t = cells_[(static_cast<std::size_t>(z) * n_[1] + y) * n_[0] + x];
          if (t != kNoId) out.push_back(t);
        }
}

Location PointLocator::locate(const Point& p, TetId hint) const {
  auto miss = [&](const Location& l) {
    if (l.inside) return 0.0;
    const auto& v = mesh_.tet(l.tet);
    Point q = Point::Zero();
    for (int k = 0; k < 4; ++k) q += l.bary[k] * mesh_.point(v[k]);
    return (q - p).norm();
  };
  Location best = metrica::locate(mesh_, p, hint);
  double best_miss = miss(best);
  if (best_miss <= round_off_) return best;
  std::vector<TetId> starts;
  grid_tets(p, starts);
  for (TetId start : starts) {
    const Location again = metrica::locate(mesh_, p, start);
    if (again.inside) return again;
    if (const double m = miss(again); m < best_miss) {
      best = again;
      best_miss = m;
    }
  }
  // A walk from a tet a cell away that stops within a cell of p: p lies
  // outside, beyond a boundary near it (a curved wall faceted differently).
  if (best_miss <= std::max(round_off_, cell_.norm())) return best;
  // Last, for the rare walk blocked on its way: every tet, the one holding
  // p or the nearest to it.
  for (TetId t = 0; t < mesh_.tet_capacity(); ++t) {
    if (!mesh_.tet_alive(t)) continue;
    const auto l = barycentric(mesh_, t, p);
    if (*std::min_element(l.begin(), l.end()) < -1e-12) {
      Location c;
      c.tet = t;
      c.bary = clamped(l);
      if (const double m = miss(c); m < best_miss) {
        best = c;
        best_miss = m;
      }
      continue;
    }
    Location in;
    in.tet = t;
    in.bary = clamped(l);
    in.inside = true;
    return in;
  }
  return best;
}

std::vector<double> interpolate_vertex_values(const Mesh& from, const std::vector<double>& values, int width,
                                              const Mesh& to, std::size_t* outside) {
  if (width < 1) throw InputError(fmt::format("interpolate: {} values per vertex", width));
  const auto w = static_cast<std::size_t>(width);
  if (values.size() != from.vertex_capacity() * w)
    throw InputError(fmt::format("interpolate: {} values for a mesh of {} vertex ids ({} per vertex)", values.size(),
                                 from.vertex_capacity(), width));
  std::vector<double> out(to.vertex_capacity() * w, 0.0);
  const PointLocator locator(from);
  std::size_t n_outside = 0;
  TetId hint = kNoId;
  for (VertexId v = 0; v < to.vertex_capacity(); ++v) {
    if (!to.vertex_alive(v)) continue;
    const Location loc = locator.locate(to.point(v), hint);
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
