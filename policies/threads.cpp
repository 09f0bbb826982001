#include <metrica/policies/threads.hpp>

#include <omp.h>

namespace metrica {

int thread_count() { return omp_get_max_threads(); }

void set_thread_count(int n) { omp_set_num_threads(n > 0 ? n : omp_get_num_procs()); }

int core_count() { return omp_get_num_procs(); }

}  // namespace metrica
