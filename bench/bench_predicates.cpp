// Cost of the predicates under each Precision policy, in ns per call
// (median of several runs over the same inputs), and the share of calls
// that the Filtered policy's floating-point filters cannot decide, i.e.
// that reach its exact stage; on random and on near-degenerate inputs.
//
//   build/bench/bench_predicates [calls=200000] [runs=5]
#include "bench_common.hpp"

#include <metrica/policies/threads.hpp>
#include <metrica/predicates/precision.hpp>

#include <fmt/core.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace metrica;
using Five = std::array<Point, 5>;

// random: uniform in [-1,1]^3. coplanar: integer points of z = 1 moved by
// 2^-45 (orient3d near zero). cospherical: integer points of |x|^2 = 9
// moved by 2^-45 (insphere near zero).
std::vector<Five> inputs(const std::string& kind, std::size_t n) {
  std::mt19937_64 r(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> coin(-1, 1), pick(0, 11), grid(-8, 8);
  const std::array<Point, 12> sphere = {Point(3, 0, 0),  Point(-3, 0, 0), Point(0, 3, 0),   Point(0, -3, 0),
                                        Point(0, 0, 3),  Point(0, 0, -3), Point(1, 2, 2),   Point(2, 1, -2),
                                        Point(-2, 2, 1), Point(2, -2, 1), Point(-1, -2, 2), Point(2, 2, -1)};
  const double tiny = std::ldexp(1.0, -45);
  std::vector<Five> out(n);
  for (auto& x : out) {
    for (auto& p : x) {
      if (kind == "random")
        p = Point(u(r), u(r), u(r));
      else if (kind == "coplanar")
        p = Point(grid(r), grid(r), 1.0) + tiny * Point(coin(r), coin(r), coin(r));
      else
        p = sphere[pick(r)] + tiny * Point(coin(r), coin(r), coin(r));
    }
  }
  return out;
}

template <class P>
std::array<double, 2> ns_per_call(const std::vector<Five>& in, int runs) {
  volatile int sink = 0;
  const double to = bench::median_seconds(runs, [&] {
    int s = 0;
    for (const auto& x : in) s += P::orient3d(x[0], x[1], x[2], x[3]);
    sink = sink + s;
  });
  const double ts = bench::median_seconds(runs, [&] {
    int s = 0;
    for (const auto& x : in) s += P::insphere(x[0], x[1], x[2], x[3], x[4]);
    sink = sink + s;
  });
  const double n = static_cast<double>(in.size());
  return {1e9 * to / n, 1e9 * ts / n};
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t calls = argc > 1 ? std::stoul(argv[1]) : 200000;
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  fmt::print("predicates: {} calls per input kind, median of {} runs, {} cores\n\n", calls, runs,
             metrica::core_count());
  fmt::print("{:<12} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>11} {:>11}\n", "input", "orient", "orient", "orient",
             "insphere", "insphere", "insphere", "orient", "insphere");
  fmt::print("{:<12} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>11} {:>11}\n", "", "fast ns", "filt ns", "exact ns",
             "fast ns", "filt ns", "exact ns", "exact share", "exact share");
  for (const std::string kind : {"random", "coplanar", "cospherical"}) {
    const auto in = inputs(kind, calls);
    const auto f = ns_per_call<metrica::Fast>(in, runs);
    const auto g = ns_per_call<metrica::Filtered>(in, runs);
    const auto e = ns_per_call<metrica::Exact>(in, std::max(1, runs / 2));
    std::size_t orient_exact = 0, sphere_exact = 0;
    for (const auto& x : in) {
      orient_exact += !metrica::orient3d_filter_decides(x[0], x[1], x[2], x[3]);
      sphere_exact += !metrica::insphere_filter_decides(x[0], x[1], x[2], x[3], x[4]);
    }
    const double n = static_cast<double>(in.size());
    fmt::print("{:<12} {:>10.1f} {:>10.1f} {:>10.1f} {:>10.1f} {:>10.1f} {:>10.1f} {:>10.3f}% {:>10.3f}%\n", kind, f[0],
               g[0], e[0], f[1], g[1], e[1], 100.0 * static_cast<double>(orient_exact) / n,
               100.0 * static_cast<double>(sphere_exact) / n);
  }
  return 0;
}
