// A way to run the parts of a sweep on several threads without the core
// knowing about OpenMP: a Concurrency policy's parallel_for behind a
// std::function, called once per sweep (not per element), so the type
// erasure costs nothing measurable. Mesh::compact takes one; adapt hands
// it part_runner<C>(n) (policies/concurrency.hpp). sort_in_parts is the
// parallel sort of both (compaction's and the Speculative policy's).
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <utility>
#include <vector>

namespace metrica {

// [first, last) of part p when n items are cut into `parts`.
inline std::pair<std::size_t, std::size_t> part_slice(std::size_t n, std::size_t parts, std::size_t p) {
  return {n * p / parts, n * (p + 1) / parts};
}

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

// Sorts [first, last) by `less` in `parts` parts: each part's slice sorted
// on its own, then neighbouring slices merged pairwise in rounds, where
// run(n, f) runs f(0) .. f(n - 1), possibly concurrently (a PartRunner or
// a policy's parallel_for). Not stable; the result is sorted for any
// number of parts.
template <class It, class Less, class Run>
void sort_in_parts(It first, It last, Less less, std::size_t parts, Run&& run) {
  const auto n = static_cast<std::size_t>(std::distance(first, last));
  parts = std::max<std::size_t>(parts, 1);
  auto cut = [&](std::size_t p) { return first + static_cast<std::ptrdiff_t>(n * p / parts); };
  run(parts, [&](std::size_t p) { std::sort(cut(p), cut(p + 1), less); });
  for (std::size_t width = 1; width < parts; width *= 2) {
    const std::size_t pairs = (parts + 2 * width - 1) / (2 * width);
    run(pairs, [&](std::size_t k) {
      const std::size_t lo = 2 * width * k, mid = std::min(parts, lo + width), hi = std::min(parts, lo + 2 * width);
      if (mid < hi) std::inplace_merge(cut(lo), cut(mid), cut(hi), less);
    });
  }
}

// The lists joined in order into one; list p is copied by run's part p
// (run(n, f) as in sort_in_parts), so no thread copies them all.
template <class T, class Run>
std::vector<T> join_in_parts(const std::vector<std::vector<T>>& lists, Run&& run) {
  std::vector<std::size_t> offset(lists.size() + 1, 0);
  for (std::size_t p = 0; p < lists.size(); ++p) offset[p + 1] = offset[p] + lists[p].size();
  std::vector<T> all(offset.back());
  run(lists.size(), [&](std::size_t p) {
    std::copy(lists[p].begin(), lists[p].end(), all.begin() + static_cast<std::ptrdiff_t>(offset[p]));
  });
  return all;
}

}  // namespace metrica
