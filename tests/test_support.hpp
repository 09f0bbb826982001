// Helpers shared by the tests: data paths, temporary folders, a seeded
// random generator whose seed is printed and can be overridden
// (METRICA_TEST_SEED=N) to replay a failure.
#pragma once

#include <metrica/geometry.hpp>
#include <metrica/io/mesh_data.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/sym_tensor.hpp>
#include <metrica/part_runner.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <unistd.h>

namespace metrica::test {

inline std::string ugawg(const std::string& name) { return std::string(METRICA_UGAWG_DIR) + "/" + name; }

inline std::uint64_t seed() {
  static const std::uint64_t s = [] {
    const char* env = std::getenv("METRICA_TEST_SEED");
    const std::uint64_t v = env ? std::strtoull(env, nullptr, 10) : 20261122ull;
    std::fprintf(stderr, "random seed %llu (set METRICA_TEST_SEED to override)\n", static_cast<unsigned long long>(v));
    return v;
  }();
  return s;
}

inline std::mt19937_64 rng(std::uint64_t stream = 0) {
  return std::mt19937_64(seed() + stream * 0x9e3779b97f4a7c15ull);
}

// `parts` parts run in reverse order on the calling thread: a result that
// depends on the order of the parts shows.
inline PartRunner reversed_parts(std::size_t parts) {
  return PartRunner{parts, [](std::size_t n, const std::function<void(std::size_t)>& f) {
                      for (std::size_t p = n; p-- > 0;) f(p);
                    }};
}

// A point of three draws in a fixed order, last coordinate first: the order
// in which GCC evaluated the argument list Point(d(r), d(r), d(r)) (which
// is unspecified; clang takes the other), so that every compiler builds the
// same seeded cases.
template <class Dist>
Point draw_point(Dist& d, std::mt19937_64& r) {
  const double z = d(r), y = d(r), x = d(r);
  return Point(x, y, z);
}

// Lists each tet's vertices so that it is positively oriented.
inline void orient_positively(io::MeshData& d) {
  for (auto& t : d.tets)
    if (orient3d_fast(d.vertices[t[0]], d.vertices[t[1]], d.vertices[t[2]], d.vertices[t[3]]) < 0)
      std::swap(t[2], t[3]);
}

// A random SPD tensor with eigenvalues spread over [1, ratio] times a
// random scale in [1e-4, 1e4], in random principal axes.
inline Sym6 random_metric(std::mt19937_64& r, double ratio) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 1.0);
  const double q3 = u(r), q2 = u(r), q1 = u(r), q0 = u(r);  // draw_point's order
  const Eigen::Quaterniond q(Eigen::Vector4d(q0, q1, q2, q3).normalized());
  const Eigen::Vector3d l(1.0, std::pow(ratio, e(r)), ratio);
  return to_sym6(q.toRotationMatrix() * (l * std::pow(10.0, 4 * u(r))).asDiagonal() * q.toRotationMatrix().transpose());
}

// |a - b| / |b| in the Frobenius norm.
inline double rel_diff(const Sym6& a, const Sym6& b) {
  return (to_matrix(a) - to_matrix(b)).norm() / to_matrix(b).norm();
}

// A fresh folder under the system temp dir, removed at scope exit.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("metrica-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Silences warnings for the scope (tests that provoke them on purpose).
class QuietLog {
 public:
  QuietLog() : saved_(log::level()) { log::set_level(log::Level::quiet); }
  ~QuietLog() { log::set_level(saved_); }

 private:
  log::Level saved_;
};

}  // namespace metrica::test
