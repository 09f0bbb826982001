// Helpers shared by the benchmarks: the median wall time of several runs.
#pragma once

#include <metrica/timer.hpp>

#include <algorithm>
#include <vector>

namespace metrica::bench {

template <class F>
double median_seconds(int runs, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    Stopwatch clock;
    f();
    t.push_back(clock.seconds());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace metrica::bench
