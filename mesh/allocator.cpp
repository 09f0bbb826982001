#include <metrica/allocator.hpp>

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string_view>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace metrica {
namespace {

bool env_set(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && std::string_view(v) != "0";
}

#if defined(__linux__)
constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kPage = 4096;

std::size_t mapped_size(std::size_t bytes) { return (bytes + kPage - 1) / kPage * kPage; }

// Maps `size` bytes (a multiple of the page) starting on a huge page: one
// mapping of size + 2 MiB, the head and tail beyond the aligned block
// given back at once.
void* map_aligned(std::size_t size) {
  void* raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto begin = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (begin + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > begin) munmap(raw, aligned - begin);
  const std::uintptr_t tail = begin + size + kHugePage - (aligned + size);
  if (tail > 0) munmap(reinterpret_cast<void*>(aligned + size), tail);
  void* p = reinterpret_cast<void*>(aligned);
#if defined(MADV_HUGEPAGE)
  // Advice only: where THP is off this does nothing.
  static const bool wanted = !env_set("METRICA_NO_HUGE_PAGES");
  if (wanted) madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

#endif

}  // namespace

void keep_freed_memory() {
  // The opt-out, for memory-tight runs.
  if (env_set("METRICA_RETURN_FREED_MEMORY")) return;
#if defined(__GLIBC__)
  // Blocks below 4 MiB come from the heap and go back to it, the heap's
  // top released only beyond 2 GB of free memory; larger ones (a pass's
  // seed lists) are mapped and unmapped, as large blocks are
  // (allocate_large): kept in the heap, they held it at its highest
  // (103 MB for 22 MB in use at 4.3M tets).
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

void release_freed_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

FreedMemoryKeptForRun::FreedMemoryKeptForRun() { keep_freed_memory(); }

FreedMemoryKeptForRun::~FreedMemoryKeptForRun() {
  release_freed_memory();
#if defined(__GLIBC__)
  if (!env_set("METRICA_RETURN_FREED_MEMORY")) mallopt(M_TRIM_THRESHOLD, 128 * 1024);  // glibc's default
#endif
}

void* allocate_large(std::size_t bytes) {
#if defined(__linux__)
  return map_aligned(mapped_size(bytes));
#else
  void* p = std::malloc(bytes);
  if (p == nullptr) throw std::bad_alloc();
  return p;
#endif
}

void free_large(void* p, std::size_t bytes) noexcept {
  if (p == nullptr) return;
#if defined(__linux__)
  munmap(p, mapped_size(bytes));
#else
  (void)bytes;
  std::free(p);
#endif
}

void release_large_pages(void* p, std::size_t bytes) noexcept {
#if defined(__linux__)
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + kPage - 1) / kPage * kPage, last = (begin + bytes) / kPage * kPage;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace metrica
