// gmsh sets OpenMP's thread count to its own option (General.NumThreads,
// 1 by default) when it initialises and when it meshes: a KeepThreads in
// scope puts the caller's count back when it ends. Internal header.
#pragma once

#include <omp.h>

namespace metrica::detail {

class KeepThreads {
 public:
  KeepThreads() : n_(omp_get_max_threads()) {}
  ~KeepThreads() { omp_set_num_threads(n_); }
  KeepThreads(const KeepThreads&) = delete;
  KeepThreads& operator=(const KeepThreads&) = delete;

 private:
  int n_;
};

}  // namespace metrica::detail
