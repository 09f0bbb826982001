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

// The threads to use of `wanted` when `runnable` tasks of the machine,
// `own` of them this process's (at least the caller), are ready to run on
// `cores`: the cores the other processes leave, at least one, at most
// `wanted`. Threads beyond the free cores share one with a busy process,
// and each pass then waits for the thread that process delays.
int threads_for_load(int wanted, int cores, int runnable, int own);
// The tasks of the machine ready to run now, the caller among them
// (/proc/loadavg's fourth field); 0 when unknown, or when this process may
// not use every core of the machine (then the count is not its cores').
int runnable_tasks();
// This process's threads ready to run now (state R in /proc/self/task);
// 0 when unknown. Threads that wait passively between passes sleep.
int own_runnable_threads();

}  // namespace metrica
