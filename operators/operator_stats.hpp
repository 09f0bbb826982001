// What an operator pass reports: attempts, changes, rejections by the
// geometric criterion, conflicts with other threads (Speculative only),
// and time. Printed per cycle by the pipeline.
#pragma once

#include <cstddef>

namespace metrica {

struct OperatorStats {
  std::size_t tried = 0, applied = 0, rejected = 0, deferred = 0, conflicts = 0;
  double seconds = 0.0;
  OperatorStats& operator+=(const OperatorStats& o) {
    tried += o.tried;
    applied += o.applied;
    rejected += o.rejected;
    deferred += o.deferred;
    conflicts += o.conflicts;
    seconds += o.seconds;
    return *this;
  }
};

}  // namespace metrica
