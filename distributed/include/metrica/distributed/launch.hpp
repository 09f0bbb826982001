// MPI for a process that may or may not run under mpirun: initialised
// only when the launcher says so (its environment), so that `metrica`
// alone starts as fast as without MPI, and finalised at the end.
#pragma once

namespace metrica::distributed {

class MpiRuntime {
 public:
  // Initialises MPI (threads funnelled: OpenMP inside a rank, MPI on its
  // main thread) when launched by mpirun or srun.
  MpiRuntime(int* argc, char*** argv);
  ~MpiRuntime();
  MpiRuntime(const MpiRuntime&) = delete;
  MpiRuntime& operator=(const MpiRuntime&) = delete;

  // Ranks in the job (1 alone) and this one's.
  static int size();
  static int rank();
  // Ranks on this node (the default thread count shares its cores).
  static int local_size();
};

}  // namespace metrica::distributed
