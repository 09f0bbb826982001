// The operation protocol and the one pass runner.
//
// An operation (split, centroid insertion, collapse, each flip, the
// smoothing move) is a class with an item type, a scratch type, a plan
// type and four steps:
//
//   seed(mesh, item, scratch, out)    the vertices to hold before reading
//                                     around the item (from the item, or
//                                     peeked: Mesh::peek_tet);
//   find(mesh, item, scratch, out)    with the seed held: is the item still
//                                     there, and the rest of its cavity;
//   decide(mesh, item, scratch)       reads the cavity, returns a plan or
//                                     a refusal; writes nothing to the
//                                     mesh (it gets a const Mesh&) but its
//                                     quality cache (the held cavity's
//                                     mean ratios; check_plans verifies);
//   apply(mesh, item, plan, scratch)  writes the plan.
//
// A plan is valid with the scratch it was decided with, until the next
// seed, find or decide on that scratch: larger configurations (the best
// triangulation of a shell, a collapse's balls, a split's shell) stay in
// the scratch and the plan refers to them. run_pass applies each plan
// right after its decide, with the same scratch. A scratch that derives
// from ScratchGeneration (every scratch of the library) has the contract
// enforced: through the protocol's helpers (prepare_item, decide_plan,
// apply_plan, preview_plan) a plan whose scratch has moved on is refused
// with std::logic_error.
//
// preview(mesh, item, plan, scratch, out) lists the tets a plan would
// make, at their final points, so a plan is checked (orientation, shape
// floor) without applying it.
//
// run_pass<C>(mesh, op, items) is the pass skeleton, written once: the
// per-thread scratch, seed -> hold -> liveness -> find -> hold the cavity
// -> decide -> apply, the counters and the clock. The executor is the
// Concurrency policy's for_each (replay, room, threads): Serial and
// Speculative run the same operations, and so does any new executor.
#pragma once

#include <metrica/operators/operator_stats.hpp>
#include <metrica/operators/shell.hpp>
#include <metrica/policies/concurrency.hpp>
#include <metrica/timer.hpp>

#include <fmt/format.h>

#include <concepts>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

namespace metrica {

// What became of an item before its decision.
enum class Found : std::uint8_t {
  cavity,    // still there: lock what was listed, then decide
  gone,      // changed so that it no longer exists (nothing to count)
  deferred,  // still wanted, but not now (its region changed in this pass)
};

// Why decide gave no plan.
enum class Refusal : std::uint8_t {
  rejected,        // the geometry or the criterion says no
  not_applicable,  // the topology or the vertex classes forbid it
  deferred,        // wait for the next pass (e.g. too close to a new point)
};

// A plan, or the reason there is none; `tries` counts the candidates an
// item weighed (a tet's four faces for the 2-3 flips). decide_plan stamps
// it with its scratch's generation.
template <class Plan>
class Decision {
 public:
  Decision(const Plan& plan, int tries = 1) : plan_(plan), tries_(tries), has_plan_(true) {}
  Decision(Refusal why, int tries = 1) : tries_(tries), why_(why) {}
  explicit operator bool() const { return has_plan_; }
  const Plan& plan() const { return plan_; }
  Refusal why() const { return why_; }
  int tries() const { return tries_; }
  std::uint32_t generation() const { return generation_; }
  void stamp(std::uint32_t generation) { generation_ = generation; }

 private:
  Plan plan_{};
  int tries_ = 1;
  std::uint32_t generation_ = 0;
  Refusal why_ = Refusal::rejected;
  bool has_plan_ = false;
};

// The generation of a scratch: each seed and decide through the
// protocol's helpers starts a new one, and a plan is valid only in the
// generation it was decided in (one increment and one compare per item).
struct ScratchGeneration {
  std::uint32_t generation = 0;
};

namespace detail {
template <class Scratch>
void next_generation(Scratch& s) {
  if constexpr (std::derived_from<Scratch, ScratchGeneration>) ++s.generation;
}
template <class Scratch>
std::uint32_t generation_of(const Scratch& s) {
  if constexpr (std::derived_from<Scratch, ScratchGeneration>) {
    return s.generation;
  } else {
    return 0;
  }
}
template <class Plan, class Scratch>
void require_current(const Decision<Plan>& d, const Scratch& s, std::string_view op, const char* step) {
  if (!d) throw std::logic_error(fmt::format("{}: {} of a refusal (no plan)", op, step));
  if (d.generation() != generation_of(s))
    throw std::logic_error(fmt::format("{}: {} of a plan whose scratch was seeded or decided on since", op, step));
}
}  // namespace detail

// The tets a plan makes: vertices (kNoId for the vertex it creates) and
// final points.
struct PlannedTet {
  TetVertices vertices;
  TetPoints points;
};
using PlannedTets = std::vector<PlannedTet>;

template <class Op>
concept Operation = requires(const Op& op, const Mesh& cmesh, Mesh& mesh, const typename Op::Item& item,
                             typename Op::Scratch& s, const typename Op::Plan& plan, VertexList& hold,
                             PlannedTets& planned) {
  { Op::name } -> std::convertible_to<std::string_view>;
  { op.room() } -> std::same_as<PassRoom>;
  { op.seed(cmesh, item, s, hold) } -> std::same_as<Found>;
  { op.find(cmesh, item, s, hold) } -> std::same_as<Found>;
  { op.decide(cmesh, item, s) } -> std::same_as<Decision<typename Op::Plan>>;
  { op.apply(mesh, item, plan, s) } -> std::same_as<void>;
  { op.preview(cmesh, item, plan, s, planned) } -> std::same_as<void>;
};

enum class Prepared : std::uint8_t { ready, gone, deferred, conflict };

// An item up to its decision: seed, hold the seed, check it is alive,
// find, hold the cavity. `hold(vertices)` takes the locks (false: another
// thread holds one, nothing read yet that counts). `list` is scratch for
// the vertices to hold.
template <Operation Op, class Hold>
Prepared prepare_item(const Mesh& mesh, const Op& op, const typename Op::Item& item, typename Op::Scratch& s,
                      VertexList& list, Hold&& hold) {
  list.clear();
  detail::next_generation(s);
  Found f = op.seed(mesh, item, s, list);
  if (f == Found::cavity) {
    if (!hold(view(list))) return Prepared::conflict;
    for (VertexId v : list)
      if (!mesh.vertex_alive(v)) return Prepared::gone;
    list.clear();
    f = op.find(mesh, item, s, list);
  }
  if (f == Found::gone) return Prepared::gone;
  if (f == Found::deferred) return Prepared::deferred;
  return hold(view(list)) ? Prepared::ready : Prepared::conflict;
}

// Decide, stamped with the scratch's new generation.
template <Operation Op>
Decision<typename Op::Plan> decide_plan(const Mesh& mesh, const Op& op, const typename Op::Item& item,
                                        typename Op::Scratch& s) {
  detail::next_generation(s);
  Decision<typename Op::Plan> d = op.decide(mesh, item, s);
  d.stamp(detail::generation_of(s));
  return d;
}

// Apply and preview a decided plan, refused (std::logic_error) when its
// scratch was seeded or decided on since.
template <Operation Op>
void apply_plan(Mesh& mesh, const Op& op, const typename Op::Item& item, const Decision<typename Op::Plan>& d,
                typename Op::Scratch& s) {
  detail::require_current(d, s, Op::name, "apply");
  op.apply(mesh, item, d.plan(), s);
}
template <Operation Op>
void preview_plan(const Mesh& mesh, const Op& op, const typename Op::Item& item, const Decision<typename Op::Plan>& d,
                  const typename Op::Scratch& s, PlannedTets& out) {
  detail::require_current(d, s, Op::name, "preview");
  op.preview(mesh, item, d.plan(), s, out);
}

// One item through seed, find and decide on one thread, without locks
// (tests, and a caller that ranks candidates before applying any).
template <Operation Op>
Decision<typename Op::Plan> decide_item(const Mesh& mesh, const Op& op, const typename Op::Item& item,
                                        typename Op::Scratch& s) {
  VertexList list;
  switch (prepare_item(mesh, op, item, s, list, [](std::span<const VertexId>) { return true; })) {
    case Prepared::ready: return decide_plan(mesh, op, item, s);
    case Prepared::deferred: return Refusal::deferred;
    default: return Refusal::not_applicable;
  }
}

// The pass: every item of `items` through the operation under C.
template <Concurrency C, Operation Op>
OperatorStats run_pass(Mesh& mesh, const Op& op, std::span<const typename Op::Item> items) {
  Stopwatch clock;
  OperatorStats stats;
  struct Slot {
    typename Op::Scratch scratch;
    VertexList hold;
  };
  std::vector<PerThread<Slot>> threads(static_cast<std::size_t>(C::threads()));
  const Mesh& view_only = mesh;
  auto work = [&](const typename Op::Item& item, int thread, typename C::Locks& locks) {
    auto& [x, st] = threads[static_cast<std::size_t>(thread)];
    switch (prepare_item(view_only, op, item, x.scratch, x.hold,
                         [&locks](std::span<const VertexId> v) { return locks.acquire(v); })) {
      case Prepared::conflict: return Attempt::conflict;
      case Prepared::gone: return Attempt::done;
      case Prepared::deferred:
        ++st.tried;
        ++st.deferred;
        return Attempt::done;
      case Prepared::ready: break;
    }
    const Decision<typename Op::Plan> d = decide_plan(view_only, op, item, x.scratch);
    if (d) {
      apply_plan(mesh, op, item, d, x.scratch);
      ++st.applied;
    } else if (d.why() == Refusal::rejected) {
      ++st.rejected;
    } else if (d.why() == Refusal::deferred) {
      ++st.deferred;
    } else {
      return Attempt::done;  // not applicable: not tried
    }
    ++st.tried;
    st.candidates += static_cast<std::size_t>(d.tries());
    return Attempt::done;
  };
  stats.add(C::for_each(mesh, items, op.room(), work));
  add_thread_counts(stats, threads);
  stats.seconds = clock.seconds();
  return stats;
}

template <Concurrency C, Operation Op, class List>
OperatorStats run_pass(Mesh& mesh, const Op& op, const List& items) {
  return run_pass<C>(mesh, op, std::span<const typename Op::Item>(items.data(), items.size()));
}

}  // namespace metrica
