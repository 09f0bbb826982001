// A way to run the parts of a sweep on several threads without the core
// knowing about OpenMP: a Concurrency policy's parallel_for behind a
// std::function, called once per sweep (not per element), so the type
// erasure costs nothing measurable. Mesh::compact takes one; adapt hands
// it part_runner<C>(n) (policies/concurrency.hpp).
#pragma once

#include <cstddef>
#include <functional>

namespace metrica {

struct PartRunner {
  // How many parts the sweeps are cut into (1: one part, this thread).
  std::size_t parts = 1;
  // Runs f(p) for every p in [0, n), each p once, possibly concurrently;
  // rethrows what an f threw. Empty: in order on the calling thread.
  std::function<void(std::size_t n, const std::function<void(std::size_t)>& f)> run;

  void operator()(std::size_t n, const std::function<void(std::size_t)>& f) const {
    if (run && n > 1) {
      run(n, f);
      return;
    }
    for (std::size_t p = 0; p < n; ++p) f(p);
  }
};

}  // namespace metrica
