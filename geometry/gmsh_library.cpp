#include "gmsh_library.hpp"

#include <dlfcn.h>
#include <filesystem>
#include <gmshc.h>
#include <mutex>

#ifndef METRICA_GMSH_LIBRARY
#define METRICA_GMSH_LIBRARY "libgmsh.so"
#endif

namespace metrica::gmsh_api {
namespace {

// The C API functions used, resolved from the library.
struct Table {
  decltype(&gmshInitialize) initialize = nullptr;
  decltype(&gmshFinalize) finalize = nullptr;
  decltype(&gmshOpen) open = nullptr;
  decltype(&gmshOptionSetNumber) set_number = nullptr;
  decltype(&gmshModelGetEntities) get_entities = nullptr;
  decltype(&gmshModelGetBoundary) get_boundary = nullptr;
  decltype(&gmshModelGetBoundingBox) get_bounding_box = nullptr;
  decltype(&gmshModelGetParametrizationBounds) get_parametrization_bounds = nullptr;
  decltype(&gmshModelGetValue) get_value = nullptr;
  decltype(&gmshModelGetDerivative) get_derivative = nullptr;
  decltype(&gmshModelGetNormal) get_normal = nullptr;
  decltype(&gmshModelGetPrincipalCurvatures) get_principal_curvatures = nullptr;
  decltype(&gmshModelGetParametrization) get_parametrization = nullptr;
  decltype(&gmshModelReparametrizeOnSurface) reparametrize_on_surface = nullptr;
  decltype(&gmshModelOccAddSurfaceLoop) add_surface_loop = nullptr;
  decltype(&gmshModelOccAddVolume) add_volume = nullptr;
  decltype(&gmshModelOccSynchronize) synchronize = nullptr;
  decltype(&gmshModelOccRemove) remove = nullptr;
  decltype(&gmshModelMeshClear) mesh_clear = nullptr;
  decltype(&gmshModelMeshGenerate) mesh_generate = nullptr;
  decltype(&gmshModelMeshGetNodes) get_nodes = nullptr;
  decltype(&gmshModelMeshGetElementsByType) get_elements_by_type = nullptr;
  decltype(&gmshLoggerGetLastError) last_error = nullptr;
  decltype(&gmshFree) free = nullptr;
};

Table table;
std::once_flag loaded;
std::string load_error;

template <class F>
void resolve(void* handle, F& f, const char* name) {
  f = reinterpret_cast<F>(dlsym(handle, name));
  if (f == nullptr && load_error.empty()) load_error = std::string("no symbol ") + name;
}

// The library found at configuration (its file; then its name and its
// name without the last version number, the soname, for the loader's
// search to find a copy elsewhere), then any libgmsh.so.
void load_once() {
  const std::filesystem::path configured(METRICA_GMSH_LIBRARY);
  const std::string name = configured.filename().string();
  const std::string soname = name.substr(0, name.rfind('.'));
  void* handle = nullptr;
  std::string tried;
  for (const std::string& candidate : {configured.string(), name, soname, std::string("libgmsh.so")}) {
    handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle != nullptr) break;
    const char* why = dlerror();
    tried += "\n  " + (why != nullptr ? std::string(why) : candidate);
  }
  if (handle == nullptr) {
    load_error = "gmsh's library could not be loaded (install libgmsh, e.g. scripts/setup):" + tried;
    return;
  }
  Table t;
  resolve(handle, t.initialize, "gmshInitialize");
  resolve(handle, t.finalize, "gmshFinalize");
  resolve(handle, t.open, "gmshOpen");
  resolve(handle, t.set_number, "gmshOptionSetNumber");
  resolve(handle, t.get_entities, "gmshModelGetEntities");
  resolve(handle, t.get_boundary, "gmshModelGetBoundary");
  resolve(handle, t.get_bounding_box, "gmshModelGetBoundingBox");
  resolve(handle, t.get_parametrization_bounds, "gmshModelGetParametrizationBounds");
  resolve(handle, t.get_value, "gmshModelGetValue");
  resolve(handle, t.get_derivative, "gmshModelGetDerivative");
  resolve(handle, t.get_normal, "gmshModelGetNormal");
  resolve(handle, t.get_principal_curvatures, "gmshModelGetPrincipalCurvatures");
  resolve(handle, t.get_parametrization, "gmshModelGetParametrization");
  resolve(handle, t.reparametrize_on_surface, "gmshModelReparametrizeOnSurface");
  resolve(handle, t.add_surface_loop, "gmshModelOccAddSurfaceLoop");
  resolve(handle, t.add_volume, "gmshModelOccAddVolume");
  resolve(handle, t.synchronize, "gmshModelOccSynchronize");
  resolve(handle, t.remove, "gmshModelOccRemove");
  resolve(handle, t.mesh_clear, "gmshModelMeshClear");
  resolve(handle, t.mesh_generate, "gmshModelMeshGenerate");
  resolve(handle, t.get_nodes, "gmshModelMeshGetNodes");
  resolve(handle, t.get_elements_by_type, "gmshModelMeshGetElementsByType");
  resolve(handle, t.last_error, "gmshLoggerGetLastError");
  resolve(handle, t.free, "gmshFree");
  if (!load_error.empty()) {
    load_error = "gmsh's library lacks the API Metrica uses (" + load_error + ")";
    return;
  }
  table = t;
}

const Table& api() {
  load();
  return table;
}

// Throws gmsh's last error when a call reported one.
void check(int ierr, const char* what) {
  if (ierr == 0) return;
  std::string message = what;
  char* text = nullptr;
  int ignored = 0;
  table.last_error(&text, &ignored);
  if (text != nullptr) {
    if (*text != '\0') message = text;
    table.free(text);
  }
  throw GmshError(message);
}

// An array gmsh allocated, copied and freed.
template <class T>
std::vector<T> take(T* p, std::size_t n) {
  std::vector<T> out(p, p + n);
  if (p != nullptr) table.free(p);
  return out;
}

vectorpair pairs(int* p, std::size_t n) {
  const std::vector<int> flat = take(p, n);
  vectorpair out;
  for (std::size_t i = 0; i + 1 < flat.size(); i += 2) out.emplace_back(flat[i], flat[i + 1]);
  return out;
}

std::vector<int> flat(const vectorpair& v) {
  std::vector<int> out;
  for (const auto& [d, t] : v) {
    out.push_back(d);
    out.push_back(t);
  }
  return out;
}

// A call with one array of doubles out (point -> values): the parameters
// copied (the C API takes them non-const), the result taken.
template <class Call>
std::vector<double> doubles_out(const std::vector<double>& in, const char* what, Call&& call) {
  int ierr = 0;
  std::vector<double> args = in;
  double* p = nullptr;
  std::size_t n = 0;
  call(args.data(), args.size(), &p, &n, &ierr);
  std::vector<double> out = take(p, n);
  check(ierr, what);
  return out;
}

}  // namespace

void load() {
  std::call_once(loaded, load_once);
  if (!load_error.empty()) throw GmshError(load_error);
}

void initialize() {
  int ierr = 0;
  api().initialize(0, nullptr, 1, &ierr);
  check(ierr, "initialize");
}

void finalize() {
  int ierr = 0;
  api().finalize(&ierr);
  check(ierr, "finalize");
}

void open(const std::string& file) {
  int ierr = 0;
  api().open(file.c_str(), &ierr);
  check(ierr, "open");
}

void option::setNumber(const std::string& name, double value) {
  int ierr = 0;
  api().set_number(name.c_str(), value, &ierr);
  check(ierr, "option::setNumber");
}

void model::getEntities(vectorpair& dim_tags, int dim) {
  int ierr = 0;
  int* p = nullptr;
  std::size_t n = 0;
  api().get_entities(&p, &n, dim, &ierr);
  dim_tags = pairs(p, n);
  check(ierr, "getEntities");
}

void model::getBoundary(const vectorpair& dim_tags, vectorpair& out, bool combined, bool oriented, bool recursive) {
  int ierr = 0;
  std::vector<int> in = flat(dim_tags);
  int* p = nullptr;
  std::size_t n = 0;
  api().get_boundary(in.data(), in.size(), &p, &n, combined, oriented, recursive, &ierr);
  out = pairs(p, n);
  check(ierr, "getBoundary");
}

void model::getBoundingBox(int dim, int tag, double& x0, double& y0, double& z0, double& x1, double& y1, double& z1) {
  int ierr = 0;
  api().get_bounding_box(dim, tag, &x0, &y0, &z0, &x1, &y1, &z1, &ierr);
  check(ierr, "getBoundingBox");
}

void model::getParametrizationBounds(int dim, int tag, std::vector<double>& lo, std::vector<double>& hi) {
  int ierr = 0;
  double *a = nullptr, *b = nullptr;
  std::size_t na = 0, nb = 0;
  api().get_parametrization_bounds(dim, tag, &a, &na, &b, &nb, &ierr);
  lo = take(a, na);
  hi = take(b, nb);
  check(ierr, "getParametrizationBounds");
}

void model::getValue(int dim, int tag, const std::vector<double>& param, std::vector<double>& coord) {
  coord = doubles_out(param, "getValue", [&](double* in, std::size_t k, double** p, std::size_t* n, int* e) {
    api().get_value(dim, tag, in, k, p, n, e);
  });
}

void model::getDerivative(int dim, int tag, const std::vector<double>& param, std::vector<double>& derivatives) {
  derivatives = doubles_out(param, "getDerivative", [&](double* in, std::size_t k, double** p, std::size_t* n, int* e) {
    api().get_derivative(dim, tag, in, k, p, n, e);
  });
}

void model::getNormal(int tag, const std::vector<double>& param, std::vector<double>& normals) {
  normals = doubles_out(param, "getNormal", [&](double* in, std::size_t k, double** p, std::size_t* n, int* e) {
    api().get_normal(tag, in, k, p, n, e);
  });
}

void model::getPrincipalCurvatures(int tag, const std::vector<double>& param, std::vector<double>& kmax,
                                   std::vector<double>& kmin, std::vector<double>& dmax, std::vector<double>& dmin) {
  int ierr = 0;
  std::vector<double> in = param;
  double *a = nullptr, *b = nullptr, *c = nullptr, *d = nullptr;
  std::size_t na = 0, nb = 0, nc = 0, nd = 0;
  api().get_principal_curvatures(tag, in.data(), in.size(), &a, &na, &b, &nb, &c, &nc, &d, &nd, &ierr);
  kmax = take(a, na);
  kmin = take(b, nb);
  dmax = take(c, nc);
  dmin = take(d, nd);
  check(ierr, "getPrincipalCurvatures");
}

void model::getParametrization(int dim, int tag, const std::vector<double>& coord, std::vector<double>& param) {
  param = doubles_out(coord, "getParametrization", [&](double* in, std::size_t k, double** p, std::size_t* n, int* e) {
    api().get_parametrization(dim, tag, in, k, p, n, e);
  });
}

void model::reparametrizeOnSurface(int dim, int tag, const std::vector<double>& param, int surface,
                                   std::vector<double>& surface_param, int which) {
  surface_param =
      doubles_out(param, "reparametrizeOnSurface", [&](double* in, std::size_t k, double** p, std::size_t* n, int* e) {
        api().reparametrize_on_surface(dim, tag, in, k, surface, p, n, which, e);
      });
}

int model::occ::addSurfaceLoop(const std::vector<int>& surfaces, int tag, bool sewing) {
  int ierr = 0;
  std::vector<int> in = surfaces;
  const int out = api().add_surface_loop(in.data(), in.size(), tag, sewing, &ierr);
  check(ierr, "occ::addSurfaceLoop");
  return out;
}

int model::occ::addVolume(const std::vector<int>& shells) {
  int ierr = 0;
  std::vector<int> in = shells;
  const int out = api().add_volume(in.data(), in.size(), -1, &ierr);
  check(ierr, "occ::addVolume");
  return out;
}

void model::occ::synchronize() {
  int ierr = 0;
  api().synchronize(&ierr);
  check(ierr, "occ::synchronize");
}

void model::occ::remove(const vectorpair& dim_tags, bool recursive) {
  int ierr = 0;
  std::vector<int> in = flat(dim_tags);
  api().remove(in.data(), in.size(), recursive, &ierr);
  check(ierr, "occ::remove");
}

void model::mesh::clear() {
  int ierr = 0;
  api().mesh_clear(nullptr, 0, &ierr);
  check(ierr, "mesh::clear");
}

void model::mesh::generate(int dim) {
  int ierr = 0;
  api().mesh_generate(dim, &ierr);
  check(ierr, "mesh::generate");
}

void model::mesh::getNodes(std::vector<std::size_t>& nodes, std::vector<double>& coord, std::vector<double>& param,
                           int dim, int tag, bool include_boundary, bool return_param) {
  int ierr = 0;
  std::size_t* a = nullptr;
  double *b = nullptr, *c = nullptr;
  std::size_t na = 0, nb = 0, nc = 0;
  api().get_nodes(&a, &na, &b, &nb, &c, &nc, dim, tag, include_boundary, return_param, &ierr);
  nodes = take(a, na);
  coord = take(b, nb);
  param = take(c, nc);
  check(ierr, "mesh::getNodes");
}

void model::mesh::getElementsByType(int type, std::vector<std::size_t>& elements, std::vector<std::size_t>& nodes,
                                    int tag) {
  int ierr = 0;
  std::size_t *a = nullptr, *b = nullptr;
  std::size_t na = 0, nb = 0;
  api().get_elements_by_type(type, &a, &na, &b, &nb, tag, 0, 1, &ierr);
  elements = take(a, na);
  nodes = take(b, nb);
  check(ierr, "mesh::getElementsByType");
}

}  // namespace metrica::gmsh_api
