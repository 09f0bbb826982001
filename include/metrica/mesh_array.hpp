// The mesh's per-entity arrays, and how they grow on several threads.
//
// A MeshArray is a std::vector whose allocator default-initialises what it
// constructs without a value: resizing an array of ids, points or
// tensors writes nothing, so the thread that resizes does not also write
// (and page-fault) every new element on its own. grow_array then copies
// and fills in parts on a PartRunner's threads: a split pass reserves
// room for millions of tets (Mesh::add_dead_room), and compaction
// gathers into arrays that need no zero-fill first.
#pragma once

#include <metrica/allocator.hpp>
#include <metrica/ids.hpp>
#include <metrica/part_runner.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace metrica {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  // Blocks of kLargeBlock bytes and more on huge pages (allocator.hpp).
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) < kLargeBlock) return std::allocator<T>::allocate(n);
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kLargeBlock)
      std::allocator<T>::deallocate(p, n);
    else
      free_large(p, n * sizeof(T));
  }

  // No value: nothing written. Default-initialisation for a class type
  // with a default constructor of its own; the bytes left as they are for
  // an implicit-lifetime type (trivially copyable and destructible: ids,
  // points, tensors, and FaceRef, whose member initialiser would
  // otherwise write every new adjacency entry on one thread). Every such
  // resize is followed by a fill or a gather.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    if constexpr (!(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>))
      ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using MeshArray = std::vector<T, DefaultInitAllocator<T>>;

// Makes `a` `size` long (size >= a.size()), the new elements left
// unwritten (not resident, in a large block, until someone writes them),
// its capacity at least `capacity` when it has to reallocate: the copy
// into the new block cut into run.parts parts.
template <class T>
void extend_array(MeshArray<T>& a, std::size_t size, std::size_t capacity, const PartRunner& run) {
  const std::size_t old = a.size();
  if (size <= old) return;
  const std::size_t parts = std::max<std::size_t>(run.parts, 1);
  if (a.capacity() < size) {
    MeshArray<T> fresh;
    fresh.reserve(std::max(capacity, size));
    fresh.resize(old);
    run(parts, [&](std::size_t p) {
      const auto [first, last] = part_slice(old, parts, p);
      std::copy(a.begin() + static_cast<std::ptrdiff_t>(first), a.begin() + static_cast<std::ptrdiff_t>(last),
                fresh.begin() + static_cast<std::ptrdiff_t>(first));
    });
    a.swap(fresh);
  }
  a.resize(size);
}

// extend_array, the new elements equal to `fill` (written in parts).
template <class T>
void grow_array(MeshArray<T>& a, std::size_t size, const std::type_identity_t<T>& fill, std::size_t capacity,
                const PartRunner& run) {
  const std::size_t old = a.size();
  if (size <= old) return;
  extend_array(a, size, capacity, run);
  const std::size_t parts = std::max<std::size_t>(run.parts, 1);
  run(parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(size - old, parts, p);
    std::fill(a.begin() + static_cast<std::ptrdiff_t>(old + first), a.begin() + static_cast<std::ptrdiff_t>(old + last),
              fill);
  });
}

// a[new_of_old[i]] = old a[i] for the i with new_of_old[i] != kNoId, into
// an array of `size`. A scatter, so the old array is read once, front to
// back, and each 8 MiB read is handed back to the kernel at once (in a
// block of allocate_large): the new array fills as the old one empties
// (the order changes little from one compaction to the next) instead of
// both being whole at the peak, which compaction was. Each hand-back
// flushes the TLB of every core the process runs on: in 2 MiB steps a
// compaction on two threads took twice as long as in 8 MiB steps.
template <class T>
void permute_to(MeshArray<T>& a, std::span<const std::uint32_t> new_of_old, std::size_t size, const PartRunner& run) {
  if (a.empty()) return;
  MeshArray<T> out;
  // Room for a pass to grow into without moving the array (a copy beside
  // the old block at the peak): untouched, it is not resident.
  out.reserve(size + size / 4);
  out.resize(size);
  const bool large = a.capacity() * sizeof(T) >= kLargeBlock;
  constexpr std::size_t kChunk = (std::size_t{8} << 20) / sizeof(T);
  run(run.parts, [&](std::size_t p) {
    const auto [first, last] = part_slice(new_of_old.size(), run.parts, p);
    for (std::size_t lo = first; lo < last; lo += kChunk) {
      const std::size_t hi = std::min(last, lo + kChunk);
      for (std::size_t i = lo; i < hi; ++i)
        if (new_of_old[i] != kNoId) out[new_of_old[i]] = a[i];
      if (large) release_large_pages(a.data() + lo, (hi - lo) * sizeof(T));
    }
  });
  a = std::move(out);
}

}  // namespace metrica
