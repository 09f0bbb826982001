// A test-and-test-and-set spin lock for very short critical sections
// (a hash-set lookup), where an OS mutex would cost more than the work.
// Copying gives a new, unlocked lock: it guards its owner's data, and a
// copy of the owner has its own.
#pragma once

#include <atomic>

namespace metrica {

class SpinLock {
 public:
  SpinLock() = default;
  SpinLock(const SpinLock&) {}
  SpinLock& operator=(const SpinLock&) { return *this; }

  void lock() {
    for (;;) {
      if (!locked_.exchange(true, std::memory_order_acquire)) return;
      while (locked_.load(std::memory_order_relaxed)) {
      }
    }
  }
  void unlock() { locked_.store(false, std::memory_order_release); }

 private:
  std::atomic<bool> locked_{false};
};

}  // namespace metrica
