// The Concurrency policy: how work is found and protected (docs/architecture.md).
//
// A pass hands its work list to C::for_each with a work function
//
//   Attempt work(const Item& item, int thread, typename C::Locks& locks)
//
// which, for one item, locks vertices before it reads what they guard
// (locks.acquire: all or nothing, false = another thread holds one),
// finds its cavity, locks the cavity's vertices, then decides and writes.
// It returns Attempt::conflict when an acquisition failed (before any
// write: the item is replayed later) and Attempt::done otherwise. The
// policy releases the locks after each item. What a thread may read:
//   - the tets containing a vertex it holds (their vertices), and the
//     neighbour across a face one of whose vertices it holds: so the ball
//     of a held vertex and the shell of an edge with a held end;
//   - a tet all of whose vertices it holds, entirely (points, metrics);
//   - any tet's vertices through Mesh::peek_tet (a seed), to lock them
//     and check again.
// C::collect runs a read-only sweep (no writes to the mesh but the quality
// cache) that builds a work list, in parallel under Speculative;
// C::parallel_for(n, f) runs f(i) for each part i of such a sweep, where
// part i writes only what it owns (a slice of an array, its own marks).
// Serial runs the items in order on one thread and never conflicts;
// Speculative (speculative.hpp) runs them on all threads with per-vertex
// owner words. Operators are written once for both.
#pragma once

#include <metrica/ids.hpp>
#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

namespace metrica {

enum class Attempt : std::uint8_t { done, conflict };

// The ids one item may create at most (a thread's pool is topped up to
// this before each item), and on average (sizes the shared reserve).
struct PassRoom {
  std::size_t max_vertices = 8;
  std::size_t max_tets = 512;
  double vertices_per_item = 1.0;
  double tets_per_item = 8.0;
};

// What running a work list cost the policy: items that met a conflict
// (their locks released, nothing written), items replayed in a later
// round, rounds, and items left to one thread when rounds stalled.
struct PassTally {
  std::size_t conflicts = 0, replays = 0, rounds = 0, serial_tail = 0;
  double seconds = 0.0;  // inside for_each (the rest of a pass builds its work list)
  // Load balance: the threads' time until each ran out of items, against
  // the rounds' time times their threads (busy / thread = 1: no waiting).
  double busy_seconds = 0.0, thread_seconds = 0.0;
};

// A Concurrency policy is an executor: for_each runs a work list (the
// pass runner's work function per item, replaying conflicts, keeping room
// for what items create); the rest serves the sweeps that build lists.
template <class C>
concept Concurrency = requires(typename C::Locks& locks, std::span<const VertexId> vertices, Mesh& mesh,
                               std::span<const int> items) {
  { C::name } -> std::convertible_to<std::string_view>;
  { C::threads() } -> std::same_as<int>;
  {
    C::for_each(mesh, items, PassRoom{}, [](const int&, int, typename C::Locks&) { return Attempt::done; })
    } -> std::same_as<PassTally>;
  { locks.acquire({VertexId{0}}) } -> std::same_as<bool>;
  {
    C::template collect<int>(std::size_t{0}, [](std::size_t, std::vector<int>&) {})
    } -> std::same_as<std::vector<int>>;
  { C::sort(std::declval<int*>(), std::declval<int*>(), std::less<int>{}) } -> std::same_as<void>;
  {
    C::parallel_for(std::size_t{0}, [](std::size_t) {})
    } -> std::same_as<void>;
  { locks.acquire(vertices) } -> std::same_as<bool>;
  { locks.release() } -> std::same_as<void>;
};

struct Serial {
  static constexpr std::string_view name = "serial";
  struct Locks {
    bool acquire(std::span<const VertexId>) { return true; }
    bool acquire(std::initializer_list<VertexId>) { return true; }
    void release() {}
  };
  static int threads() { return 1; }

  // Read-only sweeps that build a work list: f(i, out) for i in [0, n)
  // appends what item i contributes; the parts keep the order of i.
  template <class T, class F>
  static std::vector<T> collect(std::size_t n, F&& f) {
    std::vector<T> out;
    for (std::size_t i = 0; i < n; ++i) f(i, out);
    return out;
  }

  // f(i) for i in [0, n), in order.
  template <class F>
  static void parallel_for(std::size_t n, F&& f) {
    for (std::size_t i = 0; i < n; ++i) f(i);
  }

  // Sorts a work list (std::sort: the same order on every run).
  template <class It, class Less>
  static void sort(It first, It last, Less less) {
    std::sort(first, last, less);
  }

  template <class Item, class Work>
  static PassTally for_each(Mesh&, std::span<const Item> items, const PassRoom&, Work&& work) {
    Stopwatch clock;
    Locks locks;
    PassTally tally;
    tally.rounds = items.empty() ? 0 : 1;
    for (const Item& item : items) work(item, 0, locks);
    tally.seconds = clock.seconds();
    return tally;
  }
};

static_assert(Concurrency<Serial>);

// How many parts a parallel_for sweep over n items (tets, edges) uses
// under C: one per thread, or one below a size where a fork costs more
// than it saves.
template <class C>
std::size_t sweep_parts(std::size_t n) {
  return n < 16384 ? 1 : static_cast<std::size_t>(std::max(1, C::threads()));
}

// C's parallel_for as a PartRunner (for the mesh core, which knows no
// policy), cut into sweep_parts<C>(n) parts.
template <class C>
PartRunner part_runner(std::size_t n) {
  return PartRunner{sweep_parts<C>(n),
                    [](std::size_t k, const std::function<void(std::size_t)>& f) { C::parallel_for(k, f); }};
}

}  // namespace metrica
