// The process's allocator, tuned for adaptation: keep freed memory for
// reuse instead of handing it back to the kernel.
//
// Every pass builds work lists and scratch arrays of tens of MB (edge
// buckets, seeds, compaction's maps) and frees them when it ends. glibc
// serves such blocks by mmap and returns them by munmap, so the next pass
// faults every page in again, zeroed by the kernel: 7-8% of a 0.94M-tet
// adaptation on one thread or two (bench_scaling 0.37: 32.8 s -> 30.3 s;
// 19.0 s -> 17.6 s), a third at 4.43M tets (bench_adapt 0.22: 210 s ->
// 138 s). Kept in the heap instead, a freed block serves the next pass's;
// the peak resident memory grows (942k tets: 265 -> 281 MB; 4.43M: 874 ->
// 1,179 MB).
//
// Process-wide, so the library never calls it: the metrica command, the
// examples and the benchmarks do at start-up; an application embedding
// Metrica may call it too. A no-op outside glibc, and when the environment
// sets METRICA_RETURN_FREED_MEMORY (to anything but 0).
#pragma once

namespace metrica {

void keep_freed_memory();

// Hands the freed memory kept in the heap back to the kernel (between
// runs of a benchmark, so that each measures its own peak).
void release_freed_memory();

}  // namespace metrica
