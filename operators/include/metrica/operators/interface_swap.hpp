// The 2-2 swap of an internal surface, at a tet between its two folds.
// Tet abcd of region R with two faces on internal surface s (abc and abd,
// the regions across them both R') lies in the fold of the surface over
// edge ab: when the two facets are nearly coplanar it is a sliver that no
// flip may remove (its faces on the surface are kept). The swap moves the
// tet to region R': its faces acd and bcd become the surface (the surface
// edge ab becomes cd) and abc, abd inner faces of R', where the flips can
// then take the sliver out. No tet changes shape; one tet changes region
// and its four faces their ids.
//
// Decided when the surface's triangles get better (the smaller mean ratio
// of the two new facets beats the old ones', so no swap undoes another),
// the new facets fit the Geometry (on a model within its deviation bound;
// without one coplanar with the old to round-off, so the regions keep
// their volumes) and cd is not yet an edge of the surface or the boundary
// (the surface stays manifold). Never on required edges or a kept surface.
#pragma once

#include <metrica/geometry/model.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/timer.hpp>

#include <cmath>
#include <vector>

namespace metrica {

struct InterfaceSwapOptions {
  // Only tets of mean ratio below this are listed.
  double below = 0.3;
  // The new facets' largest normal deviation from the old (1 - |cos|);
  // CadGeometry also allows its own bound and the old facets' deviation.
  double max_normal_deviation = 1e-9;
};

struct InterfaceSwapScratch : ScratchGeneration {
  TetVertices seen{};
  Shell shell;  // of the new surface edge cd
};

// The faces of t: the two on the surface (opposite c and d) and the two
// that become it (opposite a and b), as local indices.
struct InterfaceSwapPlan {
  int ia = -1, ib = -1, ic = -1, id = -1;
  SurfaceId surface = 0;
  int region = 0;  // R', the tet's region after the swap
};

namespace detail {
// 4 sqrt(3) area / (sum of squared edges): 1 for an equilateral triangle.
inline double triangle_mean_ratio(const Point& p, const Point& q, const Point& r) {
  const double e = (q - p).squaredNorm() + (r - q).squaredNorm() + (p - r).squaredNorm();
  return e > 0.0 ? 4.0 * std::sqrt(3.0) * triangle_area(p, q, r) / e : 0.0;
}
}  // namespace detail

template <MetricSpace S, Geometry G>
struct InterfaceSwap {
  using Item = TetId;
  using Scratch = InterfaceSwapScratch;
  using Plan = InterfaceSwapPlan;
  static constexpr std::string_view name = "interface-swap";
  InterfaceSwapOptions options;
  G geometry{};

  PassRoom room() const { return {.max_vertices = 0, .vertices_per_item = 0, .tets_per_item = 0}; }
  Found seed(const Mesh& mesh, const Item& t, Scratch& x, VertexList& hold) const {
    x.seen = mesh.peek_tet(t);
    for (VertexId v : x.seen)
      if (v == kNoId) return Found::gone;
    hold.insert(hold.end(), x.seen.begin(), x.seen.end());
    return Found::cavity;
  }
  Found find(const Mesh& mesh, const Item& t, Scratch& x, VertexList& hold) const {
    if (!mesh.tet_alive(t) || mesh.tet(t) != x.seen) return Found::gone;
    // The shell of cd, c and d opposite the surface faces (none: nothing
    // to hold, decide refuses).
    int k = 0;
    VertexId cd[2] = {kNoId, kNoId};
    for (int f = 0; f < 4; ++f)
      if (mesh.internal_surface_id(t, f) != 0 && k < 2) cd[k++] = x.seen[f];
    x.shell.tets.clear();
    if (k == 2) {
      edge_shell_from(mesh, cd[0], cd[1], t, x.shell);
      append_shell_vertices(mesh, cd[0], cd[1], x.shell, hold);
    }
    return Found::cavity;
  }
  Decision<Plan> decide(const Mesh& mesh, const Item& t, Scratch& x) const {
    if (mesh.keeps_surface() || x.shell.tets.empty()) return Refusal::not_applicable;
    const TetVertices& v = x.seen;
    Plan p;
    int on = 0;
    for (int f = 0; f < 4; ++f) {
      const SurfaceId id = mesh.internal_surface_id(t, f);
      if (id == 0) continue;
      if (++on > 2 || (p.surface != 0 && id != p.surface)) return Refusal::not_applicable;
      p.surface = id;
      (p.id < 0 ? p.id : p.ic) = f;  // the first found is opposite "d"
    }
    if (on != 2) return Refusal::not_applicable;
    for (int f = 0; f < 4; ++f)
      if (f != p.ic && f != p.id) (p.ia < 0 ? p.ia : p.ib) = f;
    const VertexId a = v[p.ia], b = v[p.ib], c = v[p.ic], d = v[p.id];
    if (mesh.is_ridge(a, b) || mesh.is_required_edge(a, b)) return Refusal::not_applicable;
    // Across the surface faces: one region R'; across the others: the
    // tet's own region R, no surface and no outer boundary.
    const int region = mesh.tet_ref(t);
    const FaceRef across_c = mesh.neighbour(t, p.ic), across_d = mesh.neighbour(t, p.id);
    p.region = mesh.tet_ref(across_c.tet());
    if (mesh.tet_ref(across_d.tet()) != p.region) return Refusal::not_applicable;
    for (int f : {p.ia, p.ib}) {
      const FaceRef n = mesh.neighbour(t, f);
      if (!n.valid() || mesh.tet_ref(n.tet()) != region) return Refusal::not_applicable;
    }
    // cd on no surface face but t's own two (which become the surface).
    for (TetId u : x.shell.tets) {
      const auto& w = mesh.tet(u);
      for (int f = 0; f < 4; ++f) {
        if (w[f] == c || w[f] == d || (u == t)) continue;
        if (mesh.is_surface_face(u, f)) return Refusal::not_applicable;
      }
    }
    // The surface's triangles get better.
    const Point &pa = mesh.point(a), &pb = mesh.point(b), &pc = mesh.point(c), &pd = mesh.point(d);
    const double before = std::min(detail::triangle_mean_ratio(pa, pb, pc), detail::triangle_mean_ratio(pa, pb, pd));
    const double after = std::min(detail::triangle_mean_ratio(pa, pc, pd), detail::triangle_mean_ratio(pb, pc, pd));
    if (!(after > before * (1.0 + 1e-9))) return Refusal::rejected;
    // The new facets fit where the old ones were.
    const Eigen::Vector3d old_normal = face_normal(mesh, a, b, c);
    if (!geometry.facet_fits(mesh, a, c, d, p.surface, old_normal, options.max_normal_deviation) ||
        !geometry.facet_fits(mesh, b, c, d, p.surface, face_normal(mesh, a, b, d), options.max_normal_deviation))
      return Refusal::rejected;
    return p;
  }
  void apply(Mesh& mesh, const Item& t, const Plan& p, Scratch&) const {
    auto set = [&](int f, SurfaceId id) {
      mesh.set_internal_surface_id(t, f, id);
      const FaceRef n = mesh.neighbour(t, f);
      mesh.set_internal_surface_id(n.tet(), n.face(), id);
      mesh.touch_tet(n.tet());
    };
    set(p.ic, 0);
    set(p.id, 0);
    set(p.ia, p.surface);
    set(p.ib, p.surface);
    mesh.set_tet_ref(t, p.region);
    mesh.touch_tet(t);
  }
  void preview(const Mesh&, const Item&, const Plan&, const Scratch&, PlannedTets&) const {}
};

// The tets with two faces on an internal surface and a mean ratio below
// o.below.
template <MetricSpace S, Concurrency C>
std::vector<TetId> interface_fold_tets(const Mesh& mesh, const InterfaceSwapOptions& o) {
  if (!mesh.has_internal_surfaces()) return {};
  return C::template collect<TetId>(mesh.tet_capacity(), [&](std::size_t i, std::vector<TetId>& part) {
    const auto t = static_cast<TetId>(i);
    if (!mesh.tet_alive(t)) return;
    int on = 0;
    for (int f = 0; f < 4; ++f) on += mesh.internal_surface_id(t, f) != 0;
    if (on == 2 && cached_mean_ratio<S>(mesh, t) < o.below) part.emplace_back(t);
  });
}

// The pass: every such tet whose swap improves the surface.
template <MetricSpace S, Concurrency C, Geometry G>
OperatorStats swap_interfaces(Mesh& mesh, const InterfaceSwapOptions& o, const G& geometry) {
  Stopwatch clock;
  OperatorStats stats;
  const std::vector<TetId> tets = interface_fold_tets<S, C>(mesh, o);
  if (!tets.empty()) stats = run_pass<C>(mesh, InterfaceSwap<S, G>{o, geometry}, tets);
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace metrica
