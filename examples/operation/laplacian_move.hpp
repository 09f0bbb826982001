// A new operation, written once for every policy (the tutorial of
// docs/writing-an-operator.md): Laplacian smoothing, which moves an
// interior vertex to the mean of its neighbours when every tet of its
// ball stays positive (positive_tet: the sign every operation decides a
// new tet's orientation by) and the ball's smallest score under Criterion
// grows.
#pragma once

#include <metrica/operators/criterion.hpp>
#include <metrica/operators/operation.hpp>
#include <metrica/operators/shell.hpp>

namespace metrica::example {

template <MetricSpace S, class Criterion = MinQuality>
struct LaplacianMove {
  using Item = VertexId;
  struct Scratch : ScratchGeneration {
    TetList ball;
    VertexList neighbours;
  };
  struct Plan {
    Point to;
  };
  static constexpr std::string_view name = "laplacian";

  // Moves create nothing.
  PassRoom room() const { return {.max_vertices = 0, .max_tets = 0, .vertices_per_item = 0, .tets_per_item = 0}; }
  // Hold v, then its ball's vertices (what decide reads, what apply writes).
  Found seed(const Mesh&, VertexId v, Scratch&, VertexList& hold) const {
    hold.push_back(v);
    return Found::cavity;
  }
  Found find(const Mesh& mesh, VertexId v, Scratch& s, VertexList& hold) const {
    if (mesh.vertex_class(v) != VertexClass::interior) return Found::gone;
    vertex_ball(mesh, v, s.ball);
    vertex_neighbours(mesh, s.ball, v, s.neighbours);
    hold.insert(hold.end(), s.neighbours.begin(), s.neighbours.end());
    return Found::cavity;
  }
  // Pure: the mean of the neighbours, kept when the ball stays positive
  // and its smallest score beats the old one.
  Decision<Plan> decide(const Mesh& mesh, VertexId v, Scratch& s) const {
    Point to = Point::Zero();
    for (VertexId u : s.neighbours) to += mesh.point(u);
    to /= static_cast<double>(s.neighbours.size());
    const double bar = Criterion::bar(min_score_of<Criterion, S>(mesh, view(s.ball)));
    for (TetId t : s.ball) {
      const TetPoints x = tet_points_moved(mesh, mesh.tet(t), v, to);
      if (!positive_tet(x[0], x[1], x[2], x[3])) return Refusal::rejected;
      if (Criterion::template tet_score_at<S>(mesh, mesh.tet(t), x) <= bar) return Refusal::rejected;
    }
    return Plan{to};
  }
  void apply(Mesh& mesh, VertexId v, const Plan& plan, Scratch& s) const {
    mesh.point(v) = plan.to;
    for (TetId t : s.ball) mesh.touch_tet(t);  // their qualities changed
  }
  void preview(const Mesh& mesh, VertexId v, const Plan& plan, const Scratch& s, PlannedTets& out) const {
    out.clear();
    for (TetId t : s.ball) out.push_back({mesh.tet(t), tet_points_moved(mesh, mesh.tet(t), v, plan.to)});
  }
};

static_assert(Operation<LaplacianMove<LogEuclidean>>);

}  // namespace metrica::example
