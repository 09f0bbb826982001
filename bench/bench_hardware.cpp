// What this machine lets two (or N) threads gain, independent of Metrica:
// the ceiling against which bench_scaling's speedups are read.
//   compute: each thread runs the same dependent floating-point chain
//            (no memory traffic); ideal: the same time on N threads.
//   gather:  a fixed number of random 8-byte reads from a 512 MB array,
//            shared out among the threads (memory latency and bandwidth,
//            what mesh passes mostly wait on); ideal: N x faster.
// Usage: bench_hardware [threads, default 2] [repeats, default 3]
// Runs 1 and N threads alternately and prints the median speedups.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <thread>
#include <vector>

namespace {

double seconds_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void on_threads(int n, const std::function<void(int)>& f) {
  std::vector<std::thread> pool;
  for (int i = 1; i < n; ++i) pool.emplace_back(f, i);
  f(0);
  for (auto& t : pool) t.join();
}

volatile double compute_sink = 0;
volatile std::uint64_t gather_sink = 0;

// Seconds for every thread to run one chain of 4e8 multiply-adds.
double compute(int threads) {
  return seconds_of([&] {
    on_threads(threads, [](int id) {
      double x = 1.0 + id * 1e-9;
      for (long i = 0; i < 400'000'000L; ++i) {
        x = x * 1.0000001 + 1e-9;
        if (x > 2.0) x -= 1.0;
      }
      compute_sink = x;
    });
  });
}

// Seconds for 1e8 random reads in all, shared out among the threads.
double gather(int threads, const std::vector<std::uint64_t>& a) {
  constexpr long kReads = 100'000'000L;
  return seconds_of([&] {
    on_threads(threads, [&](int id) {
      std::uint64_t s = 12345u * static_cast<std::uint64_t>(id + 1), acc = 0;
      for (long i = 0; i < kReads / threads; ++i) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        acc += a[(s >> 20) % a.size()];
      }
      gather_sink = gather_sink + acc;
    });
  });
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::max(2, std::atoi(argv[1])) : 2;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::vector<std::uint64_t> a(std::size_t{64} << 20);  // 512 MB
  std::uint64_t s = 1;
  for (auto& x : a) x = (s = s * 6364136223846793005ULL + 1) >> 33;
  std::vector<double> compute_ratio, gather_ratio;
  for (int r = 0; r < repeats; ++r) {
    const double c1 = compute(1), cn = compute(n);
    const double g1 = gather(1, a), gn = gather(n, a);
    // compute: n threads do n times the work of one.
    compute_ratio.push_back(n * c1 / cn);
    gather_ratio.push_back(g1 / gn);
    std::printf(
        "run %d: compute 1 thread %.3f s, %d threads %.3f s (%.2fx); gather 1 thread %.3f s, %d threads %.3f s "
        "(%.2fx)\n",
        r + 1, c1, n, cn, n * c1 / cn, g1, n, gn, g1 / gn);
  }
  std::printf("%u hardware threads; median speedup on %d threads: compute %.2fx, random gather %.2fx (ideal %dx)\n",
              std::thread::hardware_concurrency(), n, median(compute_ratio), median(gather_ratio), n);
}
