// The Concurrency policy: how work is found and protected (DESIGN.md).
// An operator acquires the vertices of the cavity it will change before
// it decides or writes anything, and releases them when done:
//
//   typename C::Locks locks;            // one per worker
//   if (!locks.acquire(vertices)) ...   // all or nothing; false = conflict
//   ...decide, apply...
//   locks.release();
//
// Serial makes acquisition free and always successful; Speculative (issue
// 5) try-locks per-vertex owner words. Operators are written once for both.
#pragma once

#include <metrica/ids.hpp>

#include <concepts>
#include <span>
#include <string_view>

namespace metrica {

template <class C>
concept Concurrency = requires(typename C::Locks& locks, std::span<const VertexId> vertices) {
  { C::name } -> std::convertible_to<std::string_view>;
  { locks.acquire(vertices) } -> std::same_as<bool>;
  { locks.release() } -> std::same_as<void>;
};

struct Serial {
  static constexpr std::string_view name = "serial";
  struct Locks {
    bool acquire(std::span<const VertexId>) { return true; }
    void release() {}
  };
};

static_assert(Concurrency<Serial>);

}  // namespace metrica
