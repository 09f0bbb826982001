#include <metrica/allocator.hpp>

#include <climits>
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

void keep_freed_memory() {
  // The opt-out, for memory-tight runs.
  const char* off = std::getenv("METRICA_RETURN_FREED_MEMORY");
  if (off != nullptr && std::string_view(off) != "0") return;
#if defined(__GLIBC__)
  // No block by mmap (large ones come from the heap and go back to it),
  // and the heap's top released only beyond 2 GB of free memory.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

void release_freed_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

void* allocate_large(std::size_t bytes) {
  // Aligned so that the block starts a huge page; its size not rounded
  // up (a 2 MiB tail per block raised the peak by a third at 0.94M tets),
  // so its last partial huge page stays in 4 KiB pages.
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  void* p = nullptr;
  if (posix_memalign(&p, kHugePage, bytes) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where THP is off this fails or does nothing, and the
  // block is an ordinary one. METRICA_NO_HUGE_PAGES (to anything but 0)
  // opts out.
  static const bool wanted = [] {
    const char* off = std::getenv("METRICA_NO_HUGE_PAGES");
    return off == nullptr || std::string_view(off) == "0";
  }();
  if (wanted) madvise(p, bytes, MADV_HUGEPAGE);
#endif
  return p;
}

void free_large(void* p) noexcept { std::free(p); }

}  // namespace metrica
