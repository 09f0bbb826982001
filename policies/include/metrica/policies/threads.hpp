// The number of threads parallel policies use. Kept behind a function so
// that <omp.h> stays inside policies/ (docs/architecture.md).
#pragma once

namespace metrica {

// Threads available to parallel work (OpenMP's current maximum).
int thread_count();
// Sets it; n <= 0 means one per core.
void set_thread_count(int n);
// Logical cores of the machine.
int core_count();

}  // namespace metrica
