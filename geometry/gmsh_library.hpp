// gmsh's API, loaded when a model is first opened (dlopen), not linked.
//
// Linked, gmsh and its OpenCASCADE libraries (about 80 shared libraries)
// were loaded and relocated at the start of every run: 40 MB resident in
// each, with or without a model (11 bytes per tet of a 4.3M-tet
// adaptation, a quarter of a 46k-tet run's memory). Here the library is
// opened on the first call, its C API (gmshc.h) resolved once, and each
// function wrapped in the shape of gmsh.h's, so that the callers read as
// with the C++ API. Errors (gmsh's, or a library that cannot be loaded)
// are thrown as GmshError with gmsh's last message.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace metrica::gmsh_api {

struct GmshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using vectorpair = std::vector<std::pair<int, int>>;

// Loads the library (once; throws GmshError when it cannot).
void load();

void initialize();
void finalize();
void open(const std::string& file);

namespace option {
void setNumber(const std::string& name, double value);
}

namespace model {
void getEntities(vectorpair& dim_tags, int dim);
void getBoundary(const vectorpair& dim_tags, vectorpair& out, bool combined, bool oriented, bool recursive);
void getBoundingBox(int dim, int tag, double& x0, double& y0, double& z0, double& x1, double& y1, double& z1);
void getParametrizationBounds(int dim, int tag, std::vector<double>& lo, std::vector<double>& hi);
void getValue(int dim, int tag, const std::vector<double>& param, std::vector<double>& coord);
void getDerivative(int dim, int tag, const std::vector<double>& param, std::vector<double>& derivatives);
void getNormal(int tag, const std::vector<double>& param, std::vector<double>& normals);
void getPrincipalCurvatures(int tag, const std::vector<double>& param, std::vector<double>& kmax,
                            std::vector<double>& kmin, std::vector<double>& dmax, std::vector<double>& dmin);
void getParametrization(int dim, int tag, const std::vector<double>& coord, std::vector<double>& param);
void reparametrizeOnSurface(int dim, int tag, const std::vector<double>& param, int surface,
                            std::vector<double>& surface_param, int which);

namespace occ {
int addSurfaceLoop(const std::vector<int>& surfaces, int tag, bool sewing);
int addVolume(const std::vector<int>& shells);
void synchronize();
void remove(const vectorpair& dim_tags, bool recursive);
}  // namespace occ

namespace mesh {
void clear();
void generate(int dim);
void getNodes(std::vector<std::size_t>& nodes, std::vector<double>& coord, std::vector<double>& param, int dim, int tag,
              bool include_boundary, bool return_param);
void getElementsByType(int type, std::vector<std::size_t>& elements, std::vector<std::size_t>& nodes, int tag);
}  // namespace mesh
}  // namespace model

}  // namespace metrica::gmsh_api
