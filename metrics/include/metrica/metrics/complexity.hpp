// Metric complexity (seed, eq. (complexity)): C(M) = sum_i sqrt(det M_i) V_i,
// V_i the dual volume of vertex i. For a unit mesh C is about the number of
// vertices divided by a constant, so it is how a target size is asked for.
// V_i is the median-dual volume, a quarter of each incident tet, which sums
// to the domain's volume exactly.
#pragma once

#include <metrica/mesh.hpp>

#include <functional>
#include <vector>

namespace metrica {

// Indexed by vertex id (0 at dead ids).
std::vector<double> dual_volumes(const Mesh& mesh);

double complexity(const std::vector<Sym6>& field, const std::vector<double>& dual_volume);
double complexity(const Mesh& mesh, const std::vector<Sym6>& field);
// The complexity of the mesh's own metric (Mesh::metric), without a copy of it.
double complexity(const Mesh& mesh);

// The complexity of a metric known everywhere (an analytic metric), the
// integral of sqrt(det M) sampled on each tet at the points of a
// barycentric lattice of order m (equal weights, all positive), m chosen so
// that about `samples` points are taken in all (at least the vertices).
// The vertex formula overestimates a metric that varies within the coarse
// tets of a start mesh by up to 10x (UGAWG linear on 48 tets); sampled, the
// estimate is within a few tens of percent: what size predictions need.
double sampled_complexity(const Mesh& mesh, const std::function<Sym6(const Point&)>& metric, double samples = 4e6);
// Its two steps, for tets held elsewhere (a distributed part): the
// lattice order for `tets` tets, and one tet's share.
int sample_order(double tets, double samples = 4e6);
double sampled_tet_complexity(const Point& a, const Point& b, const Point& c, const Point& d,
                              const std::function<Sym6(const Point&)>& metric, int order);

// Multiplies every tensor by s (sizes by 1/sqrt(s); complexity by s^1.5).
void scale_metrics(std::vector<Sym6>& field, double s);

// Scales so that the complexity becomes `target` exactly (up to
// round-off); InputError when target <= 0 or the field has none.
void scale_to_complexity(std::vector<Sym6>& field, const std::vector<double>& dual_volume, double target);

}  // namespace metrica
