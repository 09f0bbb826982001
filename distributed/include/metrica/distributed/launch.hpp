// MPI for a process that may or may not run under mpirun: initialised
// only when the launcher says so (its environment), so that `metrica`
// alone starts as fast as without MPI, and finalised at the end.
#pragma once

namespace metrica::distributed {

class MpiSession {
 public:
  // Initialises MPI (threads funnelled: OpenMP inside a rank, MPI on its
  // main thread) when launched by mpirun or srun.
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  // Ranks in the job (1 alone) and this one's.
  static int size();
  static int rank();
  // Ranks on this node (the default thread count shares its cores).
  static int local_size();
};

}  // namespace metrica::distributed
