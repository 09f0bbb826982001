// How far the boundary may move without a model. Off a model, a collapse
// on the boundary drags its faces within a normal tolerance (2 degrees):
// on a curved faceted surface each such collapse changes the domain's
// volume a little, and many of them add up. The budget bounds the sum:
// every such collapse computes its exact change of volume, takes it from
// the budget, and is refused when the running total would leave
// [-bound, bound]. The check after an adaptation then holds the volume to
// the bound the operations kept, plus round-off.
#pragma once

#include <atomic>
#include <cmath>

namespace metrica {

// The default bound, relative to the domain's volume: the volume check of
// `metrica adapt` allowed this before the operations knew of it.
inline constexpr double kDefaultVolumeBudget = 1e-4;

class VolumeBudget {
 public:
  explicit VolumeBudget(double bound = 0.0) : bound_(bound) {}
  VolumeBudget(const VolumeBudget& o) : bound_(o.bound_), total_(o.total()) {}
  VolumeBudget& operator=(const VolumeBudget& o) {
    bound_ = o.bound_;
    total_.store(o.total(), std::memory_order_relaxed);
    return *this;
  }

  // Takes `delta` when the total stays within the bound; false (nothing
  // taken) otherwise. Safe from several threads: one compare-exchange.
  bool take(double delta) const {
    double now = total_.load(std::memory_order_relaxed);
    do {
      if (!(std::abs(now + delta) <= bound_)) return false;
    } while (!total_.compare_exchange_weak(now, now + delta, std::memory_order_relaxed));
    return true;
  }
  double bound() const { return bound_; }
  // The change of volume taken so far (signed).
  double total() const { return total_.load(std::memory_order_relaxed); }

 private:
  double bound_;
  mutable std::atomic<double> total_{0.0};
};

}  // namespace metrica
