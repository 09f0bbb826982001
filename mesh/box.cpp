#include <metrica/box.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/mesh_build.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace metrica {

void check_box_spec(const BoxSpec& spec) {
  // 6 tets per hex: at most 600 million tets (a 100M-tet start is already
  // more than the UGAWG cases ever need).
  for (int k : {spec.nx, spec.ny, spec.nz})
    if (k < 1 || k > 1000) throw InputError(fmt::format("n must be in [1, 1000] (got {})", k));
  if (6.0 * spec.nx * spec.ny * spec.nz > 6e8)
    throw InputError(fmt::format("{} x {} x {} hexes make more than 600 million tets", spec.nx, spec.ny, spec.nz));
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(spec.lo[k]) <= kCoordinateLimit && std::abs(spec.hi[k]) <= kCoordinateLimit))
      throw InputError(fmt::format("the corners' coordinates must be finite and within +-{:g} (got {} and {} in {})",
                                   kCoordinateLimit, spec.lo[k], spec.hi[k], "xyz"[k]));
    if (!(spec.hi[k] - spec.lo[k] > 1e-12 * std::max(1.0, std::abs(spec.lo[k]))))
      throw InputError(
          fmt::format("need lo < hi in every direction (got {} and {} in {})", spec.lo[k], spec.hi[k], "xyz"[k]));
  }
}

io::MeshData box_mesh_data(const BoxSpec& s) {
  if (s.nx < 1 || s.ny < 1 || s.nz < 1)
    throw InputError(fmt::format("box: need at least one hex per direction, got {}x{}x{}", s.nx, s.ny, s.nz));
  if (!(s.hi.array() > s.lo.array()).all()) throw InputError("box: the upper corner must exceed the lower one");
  const std::size_t vx = s.nx + 1, vy = s.ny + 1, vz = s.nz + 1;
  if (vx * vy * vz >= std::size_t(kNoId) || 6ull * s.nx * s.ny * s.nz >= std::size_t(kNoId))
    throw InputError("box: too many entities for 32-bit ids");

  io::MeshData d;
  auto id = [&](std::size_t i, std::size_t j, std::size_t k) { return static_cast<VertexId>(i + vx * (j + vy * k)); };
  d.vertices.reserve(vx * vy * vz);
  for (std::size_t k = 0; k < vz; ++k)
    for (std::size_t j = 0; j < vy; ++j)
      for (std::size_t i = 0; i < vx; ++i) {
        // Exact end values, and lo + h*i in between.
        auto coord = [](double lo, double hi, std::size_t n, std::size_t at) {
          return at == n ? hi : lo + (hi - lo) * double(at) / double(n);
        };
        d.vertices.emplace_back(coord(s.lo.x(), s.hi.x(), s.nx, i), coord(s.lo.y(), s.hi.y(), s.ny, j),
                                coord(s.lo.z(), s.hi.z(), s.nz, k));
      }
  d.vertex_refs.assign(d.vertices.size(), 0);

  // Kuhn subdivision: one tet per permutation of the axes, walking from
  // corner 000 to 111 one axis at a time.
  static constexpr std::array<std::array<int, 3>, 6> kPerms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  d.tets.reserve(6ull * s.nx * s.ny * s.nz);
  for (std::size_t k = 0; k < std::size_t(s.nz); ++k)
    for (std::size_t j = 0; j < std::size_t(s.ny); ++j)
      for (std::size_t i = 0; i < std::size_t(s.nx); ++i)
        for (const auto& perm : kPerms) {
          std::array<std::size_t, 3> c{i, j, k};
          TetVertices t;
          t[0] = id(c[0], c[1], c[2]);
          for (int step = 0; step < 3; ++step) {
            ++c[perm[step]];
            t[step + 1] = id(c[0], c[1], c[2]);
          }
          // Odd permutations of the axes come out negatively oriented.
          const auto& p = d.vertices;
          if (orient3d_fast(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0) std::swap(t[2], t[3]);
          d.tets.push_back(t);
        }
  d.tet_refs.assign(d.tets.size(), 0);

  // Boundary: two triangles per grid square on each side, cut along the
  // same diagonal as the tets (from the lowest to the highest corner).
  auto quad = [&](VertexId a, VertexId b, VertexId c, VertexId dd, int ref) {
    // a..dd counter-clockwise; diagonal a-c joins the low and high corners.
    d.triangles.push_back({a, b, c});
    d.triangles.push_back({a, c, dd});
    d.triangle_refs.push_back(ref);
    d.triangle_refs.push_back(ref);
  };
  for (std::size_t k = 0; k < std::size_t(s.nz); ++k)
    for (std::size_t j = 0; j < std::size_t(s.ny); ++j) {
      quad(id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k), 1);
      quad(id(s.nx, j, k), id(s.nx, j + 1, k), id(s.nx, j + 1, k + 1), id(s.nx, j, k + 1), 2);
    }
  for (std::size_t k = 0; k < std::size_t(s.nz); ++k)
    for (std::size_t i = 0; i < std::size_t(s.nx); ++i) {
      quad(id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1), 3);
      quad(id(i, s.ny, k), id(i, s.ny, k + 1), id(i + 1, s.ny, k + 1), id(i + 1, s.ny, k), 4);
    }
  for (std::size_t j = 0; j < std::size_t(s.ny); ++j)
    for (std::size_t i = 0; i < std::size_t(s.nx); ++i) {
      quad(id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0), 5);
      quad(id(i, j, s.nz), id(i + 1, j, s.nz), id(i + 1, j + 1, s.nz), id(i, j + 1, s.nz), 6);
    }
  return d;
}

Mesh make_box(const BoxSpec& spec) {
  BuildOptions opt;
  opt.source = "box";
  return build_mesh(box_mesh_data(spec), opt);
}

}  // namespace metrica
