// Operators under every policy combination they are instantiated with:
// after every pass the mesh passes validate() with the volume conserved,
// and the operator did what it is for.
#include "test_support.hpp"

#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/validate.hpp>

#include <doctest/doctest.h>

using namespace metrica;

namespace {

void set_uniform_metric(Mesh& mesh, double h) {
  std::vector<Sym6> f(mesh.vertex_capacity(), isotropic_metric(h));
  assign_metric(mesh, f);
}

void require_valid(const Mesh& mesh, double volume) {
  ValidateOptions o;
  o.expected_volume = volume;
  const auto report = mesh.validate(o);
  INFO(report.to_string());
  REQUIRE(report.ok());
}

template <class S>
double longest(const Mesh& mesh) {
  double l = 0.0;
  for (const auto& [a, b] : unique_edges(mesh)) l = std::max(l, S::edge_length(mesh, a, b));
  return l;
}

template <class S, class P, class C>
struct Policies {
  using Space = S;
  using Precision = P;
  using Concurrency = C;
};

}  // namespace

#define METRICA_POLICY_COMBINATIONS                                                                       \
  Policies<LogEuclidean, Filtered, Serial>, Policies<Anisotropic, Filtered, Serial>,                     \
      Policies<Isotropic, Filtered, Serial>, Policies<LogEuclidean, Exact, Serial>,                        \
      Policies<LogEuclidean, Fast, Serial>

TEST_SUITE("invariant") {
  TEST_CASE_TEMPLATE("edge refinement leaves no edge longer than sqrt 2 and a valid mesh", T,
                     METRICA_POLICY_COMBINATIONS) {
    using S = typename T::Space;
    Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
    set_uniform_metric(mesh, 0.15);
    const std::size_t start = mesh.num_vertices();
    for (int pass = 0; pass < 30 && longest<S>(mesh) > std::sqrt(2.0); ++pass) {
      const auto st = refine_edges<S, typename T::Precision, typename T::Concurrency>(mesh);
      CHECK(st.applied > 0);
      CHECK(st.conflicts == 0);
      require_valid(mesh, 1.0);
    }
    CHECK(longest<S>(mesh) <= std::sqrt(2.0));
    CHECK(mesh.num_vertices() > 5 * start);
  }

  TEST_CASE("edge refinement on the cube-cylinder keeps ridges and surface ids") {
    const auto data = io::read_meshb(test::ugawg("cube-cylinder.meshb"));
    Mesh mesh = build_mesh(data);
    const double volume = mesh.volume();
    set_uniform_metric(mesh, 0.08);
    const auto ridges_before = mesh.ridge_edges().size();
    for (int pass = 0; pass < 3; ++pass) {
      refine_edges<LogEuclidean, Filtered, Serial>(mesh);
      require_valid(mesh, volume);
    }
    CHECK(mesh.ridge_edges().size() > ridges_before);
  }
}

TEST_SUITE("unit") {
  TEST_CASE("edge shells: closed around interior edges and open between boundary faces") {
    const Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    TetList ball;
    Shell shell;
    std::size_t closed = 0, open = 0;
    for (const auto& [a, b] : unique_edges(mesh)) {
      vertex_ball(mesh, a, ball);
      REQUIRE(edge_shell(mesh, a, b, ball, shell));
      for (TetId t : shell.tets) {
        CHECK(local_index(mesh.tet(t), a) >= 0);
        CHECK(local_index(mesh.tet(t), b) >= 0);
      }
      // Consecutive shell tets are face neighbours.
      for (std::size_t k = 0; k + 1 < shell.tets.size(); ++k) {
        bool adjacent = false;
        for (int f = 0; f < 4; ++f) adjacent = adjacent || mesh.neighbour(shell.tets[k], f).tet() == shell.tets[k + 1];
        CHECK(adjacent);
      }
      (shell.closed ? closed : open) += 1;
    }
    CHECK(closed > 0);
    CHECK(open > 0);
    vertex_ball(mesh, 0, ball);
    CHECK_FALSE(edge_shell(mesh, 0, 26, ball, shell));  // opposite corners: no edge
  }

  TEST_CASE("the metric midpoint is at equal metric distance from both ends") {
    CHECK(metric_midpoint(1.0, 1.0) == 0.5);
    for (double r : {0.01, 0.3, 2.0, 50.0}) {
      const double t = metric_midpoint(1.0, r);
      // Length from a to the point at t with geometric growth la r^s.
      auto length = [&](double s0, double s1) { return (std::pow(r, s1) - std::pow(r, s0)) / std::log(r); };
      CHECK(length(0.0, t) == doctest::Approx(length(t, 1.0)).epsilon(1e-12));
    }
  }
}
