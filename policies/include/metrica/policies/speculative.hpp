// The Speculative concurrency policy (seed, sections 3.1-3.3 and 5.6):
// threads take items of the work list directly, each locks the vertices
// of its cavity with try-locks on per-vertex owner words; on the first
// failure it releases everything it holds, the item is deferred, and the
// thread moves on. No domain decomposition, no colouring, no lock held
// while waiting (nothing ever waits).
//
// Rounds: the deferred items of all threads form the next round's list;
// when a round clears less than a tenth of its list (the same few
// cavities keep colliding) the rest runs on one thread, which cannot
// conflict. Allocation: each thread creates vertices and tets from its own
// pool, topped up from a shared reserve by one atomic step per chunk; the
// reserve grows between rounds only, so no array is reallocated under a
// running thread (parallel_ids.hpp).
//
// Memory order: a successful acquisition is an acquire, a release a
// release, so whoever locks a vertex sees every write made by its
// previous holders.
#pragma once

#include <metrica/policies/concurrency.hpp>
#include <metrica/policies/parallel_ids.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/policy_list.hpp>
#include <metrica/small_vector.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <omp.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace metrica {

// One owner word per vertex id: 0 when free, else 1 + the owner thread.
class SpeculativeOwnerTable {
 public:
  void resize(std::size_t n) {
    if (n <= size_) return;
    words_ = std::make_unique<std::atomic<std::uint32_t>[]>(n);  // value-initialised: 0
    size_ = n;
  }
  std::atomic<std::uint32_t>* data() { return words_.get(); }

 private:
  std::unique_ptr<std::atomic<std::uint32_t>[]> words_;
  std::size_t size_ = 0;
};

class SpeculativeLocks {
 public:
  // `alone`: the only thread of its pass, which no other thread can
  // conflict with: every acquisition succeeds and no owner word is
  // written (a compare-and-swap and a store per vertex saved, 2% of a
  // one-thread adaptation).
  SpeculativeLocks(std::atomic<std::uint32_t>* owners, std::uint32_t me, bool alone = false)
      : owners_(owners), me_(me), alone_(alone) {}
  SpeculativeLocks(const SpeculativeLocks&) = delete;
  SpeculativeLocks& operator=(const SpeculativeLocks&) = delete;
  ~SpeculativeLocks() { release(); }

  // All of `vertices` (those already held are skipped), or none: on
  // the first one held by another thread everything this thread holds
  // is released.
  bool acquire(std::span<const VertexId> vertices) {
    if (alone_) return true;
    for (VertexId v : vertices) {
      std::atomic<std::uint32_t>& word = owners_[v];
      std::uint32_t owner = word.load(std::memory_order_relaxed);
      if (owner == me_) continue;
      if (owner != 0 ||
          !word.compare_exchange_strong(owner, me_, std::memory_order_acquire, std::memory_order_relaxed)) {
        release();
        return false;
      }
      held_.push_back(v);
    }
    return true;
  }
  bool acquire(std::initializer_list<VertexId> vertices) {
    return acquire(std::span<const VertexId>(vertices.begin(), vertices.size()));
  }
  void release() {
    for (VertexId v : held_) owners_[v].store(0, std::memory_order_release);
    held_.clear();
  }
  std::size_t held() const { return held_.size(); }

 private:
  std::atomic<std::uint32_t>* owners_;
  std::uint32_t me_;
  bool alone_;
  boost::container::small_vector<VertexId, 128> held_;
};

// What a Speculative pass may use, read when a pass starts (set it from
// the calling thread between passes, e.g. with SpeculativeScope):
//  - threads: 0 for thread_count() (--threads, OMP_NUM_THREADS, or one per
//    core), else that many;
//  - follow_load: with threads 0, no more threads than the cores other
//    processes left free when follow_load() last looked (threads_for_load;
//    the pipeline looks before each stage; the command's default when no
//    thread count is given);
//  - small_list: a work list shorter than this runs on the calling thread,
//    without pools, while the mesh is small (under 16 x small_list tets:
//    the first cycles) or the list very short (under small_list / 16: tens
//    of items, whose fork, join and reserve cost more than their work). In
//    the first cycles a tenth of the items conflicted and their replays
//    reordered the work; such runs never recovered the quality of one
//    thread's (docs/benchmarks.md). 0 sends every list to the threads, as
//    the tests do to force interleavings on small meshes.
struct SpeculativeSettings {
  static constexpr std::size_t kSmallList = 8192;
  int threads = 0;
  bool follow_load = false;
  int load_threads = 0;  // follow_load's last count (0: none yet)
  std::size_t small_list = kSmallList;
};

// The settings in force for the scope's lifetime, the previous ones
// restored after.
class SpeculativeScope {
 public:
  explicit SpeculativeScope(SpeculativeSettings s);
  SpeculativeScope(const SpeculativeScope&) = delete;
  SpeculativeScope& operator=(const SpeculativeScope&) = delete;
  ~SpeculativeScope();

 private:
  SpeculativeSettings saved_;
};

// The speculative executor (the pipeline's default).
struct Speculative {
  static constexpr std::string_view name = "speculative";

  using OwnerTable = SpeculativeOwnerTable;
  using Locks = SpeculativeLocks;

  static SpeculativeSettings& settings();
  static int threads() {
    const SpeculativeSettings& s = settings();
    if (s.threads > 0) return s.threads;
    return s.follow_load && s.load_threads > 0 ? std::min(s.load_threads, thread_count()) : thread_count();
  }
  // With follow_load, the threads for the next passes from the machine's
  // load now (from the calling thread, between passes: a pass sizes its
  // per-thread state once).
  static void follow_load() {
    SpeculativeSettings& s = settings();
    if (!s.follow_load) return;
    const int runnable = runnable_tasks();
    s.load_threads =
        runnable > 0 ? threads_for_load(thread_count(), core_count(), runnable, own_runnable_threads()) : 0;
  }
  // "speculative on N threads, lists under M on one thread while the mesh
  // is small" (adapt -v).
  static std::string describe();

  // The owner words, at least n: kept by the calling thread from pass to
  // pass (every word is 0 again when a pass ends), so a pass neither
  // allocates nor clears them.
  static std::atomic<std::uint32_t>* owner_words(std::size_t n) {
    thread_local OwnerTable table;
    table.resize(n);
    return table.data();
  }

  // A read-only sweep over blocks of [0, n) that the threads take in
  // turn; each block appends to its own list, the lists joined in block
  // order (the order of i) by the threads. Blocks, not one static half
  // per thread: the costly items cluster (a pass's new tets sit at the
  // end of the arrays, their qualities not cached yet), and with halves
  // the flips' seed sweep ran 1.5x on two threads at 4.4M tets.
  template <class T, class F>
  static std::vector<T> collect(std::size_t n, F&& f) {
    const int nt = std::max(1, threads());
    std::vector<T> out;
    if (nt == 1 || n < 4096) {
      for (std::size_t i = 0; i < n; ++i) f(i, out);
      return out;
    }
    const std::size_t blocks = std::min<std::size_t>(static_cast<std::size_t>(nt) * 16, n / 256);
    std::vector<std::vector<T>> lists(blocks);
    std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
    for (long b = 0; b < static_cast<long>(blocks); ++b) {
      try {
        const auto [first, last] = part_slice(n, blocks, static_cast<std::size_t>(b));
        std::vector<T>& mine = lists[static_cast<std::size_t>(b)];
        for (std::size_t i = first; i < last; ++i) f(i, mine);
      } catch (...) {
#pragma omp critical(metrica_collect_error)
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
    return join_in_parts(lists, [](std::size_t k, auto&& g) { parallel_for(k, g); });
  }

  // f(i) for i in [0, n) on the policy's threads, one i per thread in
  // turn (n is a number of parts, about threads()); f(i) writes only what
  // part i owns. The first exception is rethrown after the loop.
  template <class F>
  static void parallel_for(std::size_t n, F&& f) {
    const int nt = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads())), n));
    if (nt <= 1) {
      for (std::size_t i = 0; i < n; ++i) f(i);
      return;
    }
    std::exception_ptr error;
#pragma omp parallel for num_threads(nt) schedule(static, 1)
    for (long i = 0; i < static_cast<long>(n); ++i) {
      try {
        f(static_cast<std::size_t>(i));
      } catch (...) {
#pragma omp critical(metrica_parallel_for_error)
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
  }

  // Sorts [first, last) by `less` on the policy's threads: one slice per
  // thread sorted in parallel, then merged pairwise in parallel rounds.
  // Not stable, and equal elements may end in another order than
  // std::sort's (work lists only; Serial keeps std::sort).
  template <class It, class Less>
  static void sort(It first, It last, Less less) {
    const auto n = static_cast<std::size_t>(last - first);
    const int nt = std::max(1, threads());
    if (nt == 1 || n < 32768) {
      std::sort(first, last, less);
      return;
    }
    sort_in_parts(first, last, less, static_cast<std::size_t>(nt), [](std::size_t k, auto&& f) { parallel_for(k, f); });
  }

  template <class Item, class Work>
  static PassTally for_each(Mesh& mesh, std::span<const Item> items, const PassRoom& room, Work&& work) {
    PassTally tally;
    if (items.empty()) return tally;
    Stopwatch clock;
    const std::size_t small = settings().small_list;
    if (items.size() < small && (items.size() < small / 16 || mesh.num_tets() < 16 * small)) {
      Locks locks(nullptr, 1, true);
      for (const Item& item : items) {
        if (work(item, 0, locks) == Attempt::conflict)  // one thread: never
          throw std::logic_error("Speculative: a conflict on one thread");
        locks.release();
      }
      tally.rounds = 1;
      tally.seconds = clock.seconds();
      return tally;
    }
    const int nt = std::max(1, threads());
    // Room for the list, plus a chunk per thread and the per-item margin.
    auto room_for = [&](std::size_t n, int threads_now) {
      const auto slack = static_cast<std::size_t>(threads_now) * 2048;
      auto need = [&](double per_item, std::size_t max) {
        return max == 0 ? std::size_t{0} : static_cast<std::size_t>(std::ceil(per_item * double(n))) + slack + max;
      };
      return std::pair{need(room.vertices_per_item, room.max_vertices), need(room.tets_per_item, room.max_tets)};
    };
    const auto [v0, t0] = room_for(items.size(), nt);
    // The arrays grow on the pass's threads.
    ParallelIds ids(mesh, nt, v0, t0, part_runner<Speculative>(mesh.tet_capacity()));
    struct alignas(64) PerThread {
      std::vector<Item> deferred;
      std::size_t conflicts = 0;
      double busy = 0;
      bool out_of_room = false;
      std::exception_ptr error;
    };
    std::vector<PerThread> per(static_cast<std::size_t>(nt));
    std::vector<Item> list, next;
    std::span<const Item> current = items;
    int threads_now = nt;
    for (;;) {
      std::atomic<std::uint32_t>* const words = owner_words(mesh.vertex_capacity());
      ++tally.rounds;
      if (threads_now == 1 && nt > 1) tally.serial_tail += current.size();
      // Chunks of the list: large enough to keep a thread in one region
      // of the mesh (the lists come in vertex or length order), small
      // enough to balance (32 per thread). Up to 16384 items: against
      // 1024, flip conflicts fell from 1.4% to 0.1% at 0.94M tets.
      const auto chunk = static_cast<long>(
          std::clamp<std::size_t>(current.size() / (static_cast<std::size_t>(threads_now) * 32), 16, 16384));
      const long n = static_cast<long>(current.size());
      Stopwatch round_clock;
#pragma omp parallel num_threads(threads_now)
      {
        const int tid = omp_get_thread_num();
        PerThread& mine = per[static_cast<std::size_t>(tid)];
        ids.bind(tid);
        Locks locks(words, static_cast<std::uint32_t>(tid) + 1, threads_now == 1);
#pragma omp for schedule(dynamic, chunk) nowait
        for (long i = 0; i < n; ++i) {
          const Item& item = current[static_cast<std::size_t>(i)];
          if (mine.error || !ids.fill(room.max_vertices, room.max_tets)) {
            mine.out_of_room = mine.out_of_room || !mine.error;
            mine.deferred.push_back(item);
            continue;
          }
          try {
            if (work(item, tid, locks) == Attempt::conflict) {
              ++mine.conflicts;
              mine.deferred.push_back(item);
            }
          } catch (...) {
            mine.error = std::current_exception();
          }
          locks.release();
        }
        ParallelIds::unbind();
        mine.busy += round_clock.seconds();  // until this thread ran out of items
      }
      tally.thread_seconds += round_clock.seconds() * threads_now;
      next.clear();
      bool out_of_room = false;
      std::size_t round_conflicts = 0;
      for (PerThread& p : per) {
        if (p.error) std::rethrow_exception(p.error);
        next.insert(next.end(), p.deferred.begin(), p.deferred.end());
        p.deferred.clear();
        round_conflicts += p.conflicts;
        p.conflicts = 0;
        out_of_room = out_of_room || p.out_of_room;
        p.out_of_room = false;
      }
      tally.conflicts += round_conflicts;
      if (next.empty()) break;
      tally.replays += next.size();
      // Conflicts on more than nine items in ten: the rest on one thread.
      if (10 * round_conflicts > 9 * current.size()) threads_now = 1;
      if (out_of_room) {
        const auto [v, t] = room_for(next.size(), threads_now);
        ids.grow(v, t);
      }
      std::swap(list, next);
      current = std::span<const Item>(list);
    }
    for (const PerThread& p : per) tally.busy_seconds += p.busy;
    tally.seconds = clock.seconds();
    return tally;
  }
};

static_assert(Concurrency<Speculative>);

// The concurrency policies offered by name (--concurrency), the default first.
using Concurrencies = PolicyList<Speculative, Serial>;

}  // namespace metrica
