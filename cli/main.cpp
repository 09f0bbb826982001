// metrica: one command with subcommands, like git or refine's ref.
// Exit code 0 on success, 1 on invalid input or a failed run or check, 2 on
// bad usage; errors are reported, never raised as a signal.
#include "cli.hpp"

#include <metrica/allocator.hpp>
#ifdef METRICA_HAS_MPI
#include <metrica/distributed/launch.hpp>
#endif

#include <climits>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace {

// OpenMP's threads sleep as soon as they wait (OMP_WAIT_POLICY=passive)
// unless the environment chooses: spinning, they took the core a busy
// neighbour needed and two threads ran 1.6x slower than with passive
// waiting beside a process that kept one core busy; on an idle machine
// passive costs about 1% (docs/benchmarks.md). libgomp reads the variable
// once, when it is loaded, before main (and before libc takes the
// environment, so that no earlier hook can set it): the command starts
// itself again with it set. Not under valgrind, whose tools would not
// follow.
void passive_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) return;
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (n <= 0) return;
  self[n] = '\0';
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv(self, argv);  // returns only when it failed: run as we are
}

}  // namespace

int main(int argc, char** argv) {
  passive_openmp_wait(argv);
  metrica::keep_freed_memory();  // allocator.hpp: pages reused from pass to pass
#ifdef METRICA_HAS_MPI
  const metrica::distributed::MpiRuntime mpi(&argc, &argv);
  metrica::cli::set_process_rank(metrica::distributed::MpiRuntime::rank());
#endif
  return metrica::cli::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
