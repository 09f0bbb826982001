#include <metrica/policies/threads.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <omp.h>
#include <unistd.h>

namespace metrica {

int thread_count() { return omp_get_max_threads(); }

void set_thread_count(int n) { omp_set_num_threads(n > 0 ? n : omp_get_num_procs()); }

int core_count() { return omp_get_num_procs(); }

int threads_for_load(int wanted, int cores, int runnable, int own) {
  const int others = std::max(0, runnable - std::max(1, own));
  return std::max(1, std::min(wanted, cores - others));
}

int runnable_tasks() {
  // The count is the machine's: it says nothing of the cores this process
  // may use when it may not use them all (a container's cpuset on a larger
  // host, whose tasks /proc/loadavg counts too).
  if (sysconf(_SC_NPROCESSORS_ONLN) != omp_get_num_procs()) return 0;
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (f == nullptr) return 0;
  double l1 = 0, l5 = 0, l15 = 0;
  int running = 0, total = 0;
  const int got = std::fscanf(f, "%lf %lf %lf %d/%d", &l1, &l5, &l15, &running, &total);
  std::fclose(f);
  return got == 5 ? running : 0;
}

int own_runnable_threads() {
  DIR* dir = opendir("/proc/self/task");
  if (dir == nullptr) return 0;
  int running = 0;
  char path[300];
  char line[512];
  while (const dirent* e = readdir(dir)) {
    if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
    std::snprintf(path, sizeof(path), "/proc/self/task/%s/stat", e->d_name);
    std::FILE* f = std::fopen(path, "r");
    if (f == nullptr) continue;
    const std::size_t n = std::fread(line, 1, sizeof(line) - 1, f);
    std::fclose(f);
    line[n] = '\0';
    // "tid (name) S ...": the state follows the last ')'.
    const char* close = std::strrchr(line, ')');
    if (close != nullptr && close[1] == ' ' && close[2] == 'R') ++running;
  }
  closedir(dir);
  return running;
}

}  // namespace metrica
