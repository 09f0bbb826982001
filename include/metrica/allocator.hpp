// The process's allocator, tuned for adaptation: keep freed memory for
// reuse instead of handing it back to the kernel.
//
// Every pass builds work lists and scratch arrays of tens of MB (edge
// buckets, seeds, compaction's maps) and frees them when it ends. glibc
// serves such blocks by mmap and returns them by munmap, so the next pass
// faults every page in again, zeroed by the kernel: 7-8% of a 0.94M-tet
// adaptation. Kept in the heap instead, a freed block serves the next
// pass's; the peak resident memory grows (figures: docs/benchmarks.md).
//
// Process-wide, so the library never calls it: the metrica command, the
// examples and the benchmarks do at start-up; an application embedding
// Metrica may call it too. A no-op outside glibc, and when the environment
// sets METRICA_RETURN_FREED_MEMORY (to anything but 0).
#pragma once

#include <cstddef>

namespace metrica {

void keep_freed_memory();

// Hands the freed memory kept in the heap back to the kernel (between
// runs of a benchmark, so that each measures its own peak).
void release_freed_memory();

// Large blocks (the mesh's arrays, the edge buckets) on transparent huge
// pages where the kernel offers them for the asking (Linux, THP
// "madvise" or "always", Debian's default is "madvise"): a block of at
// least kLargeBlock bytes is aligned to 2 MiB and marked MADV_HUGEPAGE.
// Why: random reads over 1 GB on this 2-core VM scaled 1.7x on two
// threads with 4 KiB pages (each miss also walks the page tables, nested
// under a hypervisor) and 2.0x on huge pages, which also made one thread
// 20% faster; over 256 MB both scaled 1.9x. The 4.4M-tet adaptation's
// working set is 1 GB. Elsewhere, or when the environment sets
// METRICA_NO_HUGE_PAGES (to anything but 0), an ordinary block.
inline constexpr std::size_t kLargeBlock = std::size_t{4} << 20;
void* allocate_large(std::size_t bytes);  // throws std::bad_alloc
void free_large(void* p) noexcept;

}  // namespace metrica
