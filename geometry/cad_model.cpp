// CadModel over gmsh's API (OpenCASCADE inside), loaded on first use
// (gmsh_library.hpp).
#include "gmsh_library.hpp"
#include "keep_threads.hpp"

#include <metrica/error.hpp>
#include <metrica/geometry/cad_model.hpp>

#include <fmt/core.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

namespace metrica {
namespace {

std::atomic<bool> model_open{false};

const std::vector<int> kNone;

// gmsh's errors (GmshError, with its last message) become an InputError
// naming what was asked.
template <class F>
auto gmsh_call(const char* what, F&& f) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(fmt::format("gmsh: {}: {}", what, e.what()));
  }
}

// Sends the process's stdout to /dev/null while in scope.
class QuietStdout {
 public:
  QuietStdout() {
    std::fflush(stdout);
    saved_ = ::dup(1);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 1);
    if (null >= 0) ::close(null);
  }
  ~QuietStdout() {
    std::fflush(stdout);
    if (saved_ >= 0) {
      ::dup2(saved_, 1);
      ::close(saved_);
    }
  }
  QuietStdout(const QuietStdout&) = delete;
  QuietStdout& operator=(const QuietStdout&) = delete;

 private:
  int saved_ = -1;
};

double wrap_near(double x, double period, double near) {
  if (period <= 0.0) return x;
  return x + period * std::round((near - x) / period);
}

}  // namespace

CadModel::CadModel(const std::string& path) : source_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such model file", path));
  if (model_open.exchange(true))
    throw std::logic_error("CadModel: gmsh holds one model per process and one is open already");
  const detail::KeepThreads keep;
  try {
    gmsh_call("initialize", [] {
      gmsh_api::initialize();
      gmsh_api::option::setNumber("General.Terminal", 0);
      gmsh_api::option::setNumber("General.Verbosity", 0);
    });
    {
      // OpenCASCADE's IGES reader prints to stdout whatever gmsh's options say.
      const QuietStdout quiet;
      gmsh_call(path.c_str(), [&] { gmsh_api::open(path); });
    }
    sew_into_volume();
    read_topology();
  } catch (...) {
    try {
      gmsh_api::finalize();
    } catch (...) {
    }
    model_open = false;
    throw;
  }
}

CadModel::~CadModel() {
  try {
    gmsh_api::finalize();
  } catch (...) {
  }
  model_open = false;
}

// IGES files (and some STEP files) hold surfaces without the volume they
// bound: sewn together, a closed set of them becomes one volume.
void CadModel::sew_into_volume() {
  gmsh_api::vectorpair volumes, surfaces;
  gmsh_api::model::getEntities(volumes, 3);
  gmsh_api::model::getEntities(surfaces, 2);
  if (!volumes.empty() || surfaces.empty()) return;
  std::vector<int> tags;
  for (auto [d, t] : surfaces) tags.push_back(t);
  try {
    const int loop = gmsh_api::model::occ::addSurfaceLoop(tags, -1, true);
    const int volume = gmsh_api::model::occ::addVolume({loop});
    gmsh_api::model::occ::synchronize();
    // Sewing made new surfaces: the old ones go.
    gmsh_api::vectorpair bounding, old;
    gmsh_api::model::getBoundary({{3, volume}}, bounding, false, false, false);
    for (const auto& s : surfaces) {
      const int tag = s.second;
      if (std::find_if(bounding.begin(), bounding.end(), [tag](const auto& b) { return std::abs(b.second) == tag; }) ==
          bounding.end())
        old.emplace_back(2, tag);
    }
    if (!old.empty()) {
      gmsh_api::model::occ::remove(old, true);
      gmsh_api::model::occ::synchronize();
    }
  } catch (...) {
    // Not closed, or not an OpenCASCADE model: the surfaces stay as they are.
  }
}

void CadModel::read_topology() {
  for (int dim = 0; dim < 4; ++dim) {
    gmsh_api::vectorpair tags;
    gmsh_api::model::getEntities(tags, dim);
    for (auto [d, t] : tags) entities_[static_cast<std::size_t>(dim)].push_back(t);
  }
  if (entities_[2].empty()) throw InputError(fmt::format("{}: the model has no surface", source_));
  double x0, y0, z0, x1, y1, z1;
  gmsh_api::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  size_ = std::sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + (z1 - z0) * (z1 - z0));
  if (!(size_ > 0.0) || !std::isfinite(size_)) size_ = 1.0;
  for (int s : entities_[2]) {
    gmsh_api::vectorpair b;
    gmsh_api::model::getBoundary({{2, s}}, b, false, false, false);
    for (auto [d, c] : b) {
      if (d != 1) continue;
      const int curve = std::abs(c);
      auto& list = curves_of_surface_[s];
      if (std::find(list.begin(), list.end(), curve) == list.end()) list.push_back(curve);
      auto& back = surfaces_of_curve_[curve];
      if (std::find(back.begin(), back.end(), s) == back.end()) back.push_back(s);
    }
  }
  for (int c : entities_[1]) {
    gmsh_api::vectorpair b;
    gmsh_api::model::getBoundary({{1, c}}, b, false, false, false);
    for (auto [d, v] : b) {
      const int vertex = std::abs(v);
      auto& list = vertices_of_curve_[c];
      if (std::find(list.begin(), list.end(), vertex) == list.end()) list.push_back(vertex);
      auto& back = curves_of_vertex_[vertex];
      if (std::find(back.begin(), back.end(), c) == back.end()) back.push_back(c);
    }
  }
  // Parameter ranges, and periods found by evaluation: a curve whose two
  // ends coincide, a surface whose two u- (or v-) borders coincide.
  const double tol = 1e-9 * size_;
  for (int dim = 1; dim <= 2; ++dim)
    for (int tag : entities_[static_cast<std::size_t>(dim)]) {
      std::vector<double> lo, hi;
      gmsh_api::model::getParametrizationBounds(dim, tag, lo, hi);
      Range r;
      for (int k = 0; k < dim; ++k) {
        r.lo[k] = lo[static_cast<std::size_t>(k)];
        r.hi[k] = hi[static_cast<std::size_t>(k)];
      }
      if (dim == 1) {
        std::vector<double> a, b;
        gmsh_api::model::getValue(1, tag, {r.lo[0]}, a);
        gmsh_api::model::getValue(1, tag, {r.hi[0]}, b);
        const bool closed = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < tol;
        if (closed) r.period[0] = r.hi[0] - r.lo[0];
      } else {
        for (int k = 0; k < 2; ++k) {
          bool same = true;
          for (double f : {0.1, 0.5, 0.9}) {
            const double other = r.lo[1 - k] + f * (r.hi[1 - k] - r.lo[1 - k]);
            std::vector<double> p0 = k == 0 ? std::vector<double>{r.lo[0], other} : std::vector<double>{other, r.lo[1]};
            std::vector<double> p1 = k == 0 ? std::vector<double>{r.hi[0], other} : std::vector<double>{other, r.hi[1]};
            std::vector<double> a, b;
            gmsh_api::model::getValue(2, tag, p0, a);
            gmsh_api::model::getValue(2, tag, p1, b);
            same = same && std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < tol;
          }
          if (same) r.period[static_cast<std::size_t>(k)] = r.hi[k] - r.lo[k];
        }
      }
      ranges_[{dim, tag}] = r;
    }
}

bool CadModel::has(int dim, int tag) const {
  if (dim < 0 || dim > 3) return false;
  const auto& list = entities_[static_cast<std::size_t>(dim)];
  return std::find(list.begin(), list.end(), tag) != list.end();
}

const std::vector<int>& CadModel::curves_of_surface(int s) const {
  const auto it = curves_of_surface_.find(s);
  return it == curves_of_surface_.end() ? kNone : it->second;
}
const std::vector<int>& CadModel::vertices_of_curve(int c) const {
  const auto it = vertices_of_curve_.find(c);
  return it == vertices_of_curve_.end() ? kNone : it->second;
}
const std::vector<int>& CadModel::curves_of_vertex(int v) const {
  const auto it = curves_of_vertex_.find(v);
  return it == curves_of_vertex_.end() ? kNone : it->second;
}
const std::vector<int>& CadModel::surfaces_of_curve(int c) const {
  const auto it = surfaces_of_curve_.find(c);
  return it == surfaces_of_curve_.end() ? kNone : it->second;
}

const CadModel::Range& CadModel::range(int dim, int tag) const {
  static const Range none;
  const auto it = ranges_.find({dim, tag});
  return it == ranges_.end() ? none : it->second;
}

Point CadModel::value(const GeoParam& g) const {
  thread_local std::vector<double> in, out;
  in.clear();
  if (g.dim >= 1) in.push_back(g.u);
  if (g.dim == 2) in.push_back(g.v);
  {
    std::lock_guard lock(lock_);
    gmsh_call("getValue", [&] { gmsh_api::model::getValue(g.dim, g.tag, in, out); });
  }
  if (out.size() < 3) throw InputError(fmt::format("gmsh: no value on entity ({}, {})", int(g.dim), g.tag));
  return Point(out[0], out[1], out[2]);
}

std::array<Eigen::Vector3d, 2> CadModel::derivatives(int surface, double u, double v) const {
  thread_local std::vector<double> in(2), out;
  in.assign({u, v});
  {
    std::lock_guard lock(lock_);
    gmsh_call("getDerivative", [&] { gmsh_api::model::getDerivative(2, surface, in, out); });
  }
  if (out.size() < 6) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  return {Eigen::Vector3d(out[0], out[1], out[2]), Eigen::Vector3d(out[3], out[4], out[5])};
}

Eigen::Vector3d CadModel::normal(int surface, double u, double v) const {
  thread_local std::vector<double> in(2), out;
  in.assign({u, v});
  {
    std::lock_guard lock(lock_);
    gmsh_call("getNormal", [&] { gmsh_api::model::getNormal(surface, in, out); });
  }
  if (out.size() < 3) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(out[0], out[1], out[2]);
}

CadModel::Curvatures CadModel::principal_curvatures(int surface, double u, double v) const {
  thread_local std::vector<double> in(2), kmax, kmin, dmax, dmin;
  in.assign({u, v});
  {
    std::lock_guard lock(lock_);
    gmsh_call("getPrincipalCurvatures",
              [&] { gmsh_api::model::getPrincipalCurvatures(surface, in, kmax, kmin, dmax, dmin); });
  }
  Curvatures c;
  if (kmax.empty() || kmin.empty() || dmax.size() < 3 || dmin.size() < 3) return c;
  c.max = kmax[0];
  c.min = kmin[0];
  c.max_direction = Eigen::Vector3d(dmax[0], dmax[1], dmax[2]);
  c.min_direction = Eigen::Vector3d(dmin[0], dmin[1], dmin[2]);
  for (auto* d : {&c.max_direction, &c.min_direction})
    if (d->norm() > 0) d->normalize();
  return c;
}

GeoParam CadModel::parametrize(int dim, int tag, const Point& p) const {
  GeoParam g;
  g.dim = static_cast<std::int8_t>(dim);
  g.tag = tag;
  if (dim == 0) return g;
  thread_local std::vector<double> out;
  {
    std::lock_guard lock(lock_);
    gmsh_call("getParametrization", [&] { gmsh_api::model::getParametrization(dim, tag, {p.x(), p.y(), p.z()}, out); });
  }
  if (out.size() < static_cast<std::size_t>(dim))
    throw InputError(fmt::format("gmsh: no parameters on entity ({}, {})", dim, tag));
  g.u = out[0];
  if (dim == 2) g.v = out[1];
  return g;
}

std::array<double, 2> CadModel::on_surface(const GeoParam& g, int surface, const std::array<double, 2>* near) const {
  std::array<double, 2> uv{g.u, g.v};
  if (g.dim == 2 && g.tag == surface) {
    // as is
  } else if (g.dim == 0 || g.dim == 1) {
    thread_local std::vector<double> in, out;
    in.clear();
    if (g.dim == 1) in.push_back(g.u);
    bool done = false;
    {
      std::lock_guard lock(lock_);
      try {
        gmsh_api::model::reparametrizeOnSurface(g.dim, g.tag, in, surface, out, 0);
        done = out.size() >= 2;
      } catch (...) {
        done = false;
      }
    }
    if (done) {
      uv = {out[0], out[1]};
    } else {
      const GeoParam q = parametrize(2, surface, value(g));
      uv = {q.u, q.v};
    }
  } else {
    const GeoParam q = parametrize(2, surface, value(g));
    uv = {q.u, q.v};
  }
  if (near != nullptr) {
    const Range& r = range(2, surface);
    for (std::size_t k = 0; k < 2; ++k) uv[k] = wrap_near(uv[k], r.period[k], (*near)[k]);
  }
  return uv;
}

double CadModel::on_curve(const GeoParam& g, int curve, const double* near) const {
  const Range& r = range(1, curve);
  double t = g.u;
  if (g.dim == 0) {
    // An end of the curve: the bound whose point it is (both on a closed
    // curve: the one nearest `near`).
    const Point p = value(g);
    const Point a = value(GeoParam{curve, 1, r.lo[0], 0.0});
    const Point b = value(GeoParam{curve, 1, r.hi[0], 0.0});
    const double da = (a - p).norm(), db = (b - p).norm();
    const double tol = 1e-7 * size_;
    if (da < tol && db < tol && near != nullptr)
      t = std::abs(*near - r.lo[0]) < std::abs(*near - r.hi[0]) ? r.lo[0] : r.hi[0];
    else if (da <= db && da < tol)
      t = r.lo[0];
    else if (db < tol)
      t = r.hi[0];
    else
      t = parametrize(1, curve, p).u;
  } else if (g.dim != 1 || g.tag != curve) {
    t = parametrize(1, curve, value(g)).u;
  }
  if (near != nullptr) t = wrap_near(t, r.period[0], *near);
  return t;
}

}  // namespace metrica
