// Runs the tutorial's operation (laplacian_move.hpp) over every vertex of
// a jittered box under Serial and Speculative, and prints what each pass
// did and how long it took:
//
//   build/examples/operation/laplacian_move [n=20] [passes=3]
#include "laplacian_move.hpp"

#include <metrica/box.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/validate.hpp>

#include <fmt/core.h>

#include <cstdlib>
#include <random>

using namespace metrica;

template <Concurrency C>
int run(int n, int passes) {
  Mesh mesh = make_box({.nx = n, .ny = n, .nz = n});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3 / n, 0.3 / n);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.vertex_class(v) == VertexClass::interior) mesh.point(v) += Point(jitter(rng), jitter(rng), jitter(rng));
  assign_metric(mesh, [](const Point&) { return isotropic_metric(1.0); });
  std::vector<VertexId> vertices;
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) vertices.push_back(v);
  for (int pass = 0; pass < passes; ++pass) {
    const OperatorStats s = run_pass<C>(mesh, example::LaplacianMove<Isotropic>{}, vertices);
    fmt::print("{:<11} pass {}: moved {} of {} tried ({} rejected) in {:.3f} s\n", C::name, pass, s.applied, s.tried,
               s.rejected, s.seconds);
  }
  return mesh.validate().ok() ? 0 : 1;
}

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 20;
  const int passes = argc > 2 ? std::atoi(argv[2]) : 3;
  return run<Serial>(n, passes) | run<Speculative>(n, passes);
}
