// Helpers shared by the benchmarks: the median wall time of several runs,
// the process's peak memory, and the adaptation case (the UGAWG `linear`
// metric scaled, on the 4x4x4 cube).
#pragma once

#include <metrica/box.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/operators/metric_source.hpp>
#include <metrica/timer.hpp>

#include <algorithm>
#include <fstream>
#include <string>
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

// Resets the peak to the current resident size (Linux: clear_refs 5).
inline void reset_peak() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
}

// Peak resident memory of this process so far (VmHWM), in bytes.
inline double peak_bytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      in >> kb;
      return kb * 1024.0;
    }
    std::getline(in, key);
  }
  return 0.0;
}

// The UGAWG `linear` metric with every size multiplied by `scale` (the tet
// count grows as scale^-3: 1 gives ~50k tets, 0.37 ~1M, 0.22 ~5M).
inline MetricFunction scaled_linear_metric(double scale) {
  return [scale](const Point& p) {
    Sym6 m = evaluate(AnalyticMetric::linear, p);
    for (double& x : m) x /= scale * scale;
    return m;
  };
}

// The 4x4x4 unit cube carrying `metric` at its vertices.
inline Mesh start_mesh(const MetricFunction& metric) {
  Mesh mesh = make_box({.nx = 3, .ny = 3, .nz = 3});
  std::vector<Sym6> f(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) f[v] = metric(mesh.point(v));
  assign_metric(mesh, f);
  return mesh;
}

}  // namespace metrica::bench
