#include <metrica/distributed/launch.hpp>

#include <cstdlib>
#include <mpi.h>

namespace metrica::distributed {

namespace {
bool g_active = false;
int g_size = 1, g_rank = 0;

bool under_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_STEP_ID"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

}  // namespace

MpiRuntime::MpiRuntime(int* argc, char*** argv) {
  if (!under_launcher()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  g_active = true;
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
}

MpiRuntime::~MpiRuntime() {
  if (g_active) MPI_Finalize();
}

int MpiRuntime::size() { return g_size; }
int MpiRuntime::rank() { return g_rank; }
int MpiRuntime::local_size() {
  if (const char* s = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) return std::max(1, std::atoi(s));
  return 1;
}

}  // namespace metrica::distributed
