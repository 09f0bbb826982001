#include <metrica/allocator.hpp>

#include <climits>
#include <cstdlib>
#include <string_view>

#if defined(__GLIBC__)
#include <malloc.h>
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

}  // namespace metrica
