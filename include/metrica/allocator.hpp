// The process's allocator, tuned for adaptation: small freed blocks kept
// for reuse, large ones handed back to the kernel.
//
// Every pass builds work lists and scratch arrays and frees them when it
// ends. Small ones (below 4 MiB) stay in the heap for reuse (glibc would
// otherwise trim and fault them in again) until the pipeline's stage ends
// (release_freed_memory in Adapter::run_stage), so they do not stand
// under the next stage's peak. Large ones are mapped and unmapped, so
// freed blocks never stay resident between live ones (docs/benchmarks.md,
// "Memory").
//
// Process-wide, so the library never calls it: the metrica command, the
// examples and the benchmarks do at start-up; an application embedding
// Metrica may call it too. A no-op outside glibc, and when the environment
// sets METRICA_RETURN_FREED_MEMORY (to anything but 0).
#pragma once

#include <cstddef>

namespace metrica {

void keep_freed_memory();

// Hands the freed memory kept in the heap back to the kernel (at the end
// of each stage of a pipeline, between runs of a benchmark). Safe in any
// process: only free blocks go.
void release_freed_memory();

// keep_freed_memory() for one run inside a process that is not ours (the
// Python module's adapt and pipeline), where glibc's adaptive mmap
// threshold would otherwise rise past the passes' large blocks and keep
// them in the heap. On leaving, the freed memory goes back to the kernel
// and the heap's top is trimmed again at glibc's default; the 4 MiB mmap
// threshold stays.
class FreedMemoryKeptForRun {
 public:
  FreedMemoryKeptForRun();
  ~FreedMemoryKeptForRun();
  FreedMemoryKeptForRun(const FreedMemoryKeptForRun&) = delete;
  FreedMemoryKeptForRun& operator=(const FreedMemoryKeptForRun&) = delete;
};

// Large blocks (the mesh's arrays, the edge buckets) are mapped on their
// own, outside the heap, starting on a 2 MiB boundary and marked
// MADV_HUGEPAGE (Linux): transparent huge pages where the kernel offers
// them for the asking (THP "madvise" or "always", Debian's default is
// "madvise"). Huge pages, because the passes read the mesh at random and
// every TLB miss walks the page tables (nested under a hypervisor on a
// VM): they speed up one thread and let two scale further. Outside the
// heap, because a growing array leaves its old block behind, and in the
// heap those blocks would stay resident between the live ones. Untouched
// pages of a block are not resident: room reserved but never written
// costs nothing. Figures: docs/benchmarks.md, "Memory". METRICA_NO_HUGE_PAGES
// (to anything but 0) leaves out the advice; elsewhere than Linux, malloc.
inline constexpr std::size_t kLargeBlock = std::size_t{4} << 20;
void* allocate_large(std::size_t bytes);               // throws std::bad_alloc
void free_large(void* p, std::size_t bytes) noexcept;  // bytes: as allocated
// Gives the kernel back the whole pages of [p, p + bytes), inside a block
// of allocate_large whose content there is no longer needed (they read as
// zeros afterwards): an array read once from front to back and then
// dropped need not stay resident behind the reading (compaction's
// scatter). A no-op elsewhere than Linux.
void release_large_pages(void* p, std::size_t bytes) noexcept;

}  // namespace metrica
