// What an operator pass reports: attempts, changes, rejections by the
// geometric criterion, conflicts with other threads (Speculative only),
// and time. Printed per cycle by the pipeline.
//
// Per-thread state of a pass (scratch and counts) sits in PerThread<T>:
// one cache-line-aligned slot per thread, so threads never share a line.
#pragma once

#include <metrica/policies/concurrency.hpp>

#include <cstddef>
#include <vector>

namespace metrica {

// Items: tried = applied + rejected + deferred (an item that no longer
// exists or to which the operation does not apply is not tried);
// candidates: the configurations the tried items weighed (a flip weighs
// several per item); conflicts: items replayed because another thread
// held their cavity (Speculative only).
struct OperatorStats {
  std::size_t tried = 0, applied = 0, rejected = 0, deferred = 0, candidates = 0, conflicts = 0;
  // Speculative: items replayed in a later round, items left to one thread.
  std::size_t replays = 0, serial_tail = 0;
  double seconds = 0.0;
  // Of `seconds`, the time in the policy's for_each (the parallel part
  // under Speculative; the rest makes work lists).
  double loop_seconds = 0.0;
  // Speculative: the threads' busy time and the loops' time x threads
  // (their ratio is the load balance).
  double busy_seconds = 0.0, thread_seconds = 0.0;
  // Counts of one thread's share of a pass.
  void add_counts(const OperatorStats& o) {
    tried += o.tried;
    applied += o.applied;
    rejected += o.rejected;
    deferred += o.deferred;
    candidates += o.candidates;
  }
  void add(const PassTally& t) {
    conflicts += t.conflicts;
    replays += t.replays;
    serial_tail += t.serial_tail;
    loop_seconds += t.seconds;
    busy_seconds += t.busy_seconds;
    thread_seconds += t.thread_seconds;
  }
  OperatorStats& operator+=(const OperatorStats& o) {
    add_counts(o);
    conflicts += o.conflicts;
    replays += o.replays;
    serial_tail += o.serial_tail;
    seconds += o.seconds;
    loop_seconds += o.loop_seconds;
    busy_seconds += o.busy_seconds;
    thread_seconds += o.thread_seconds;
    return *this;
  }
};

template <class T>
struct alignas(64) PerThread {
  T scratch;
  OperatorStats stats;
};

// Sums the threads' counts into `total`.
template <class T>
void add_thread_counts(OperatorStats& total, const std::vector<PerThread<T>>& threads) {
  for (const auto& t : threads) total.add_counts(t.stats);
}

}  // namespace metrica
