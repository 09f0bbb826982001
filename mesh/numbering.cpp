#include <metrica/numbering.hpp>

#include <atomic>

namespace metrica {

namespace {
std::atomic<int> first{1};
}

void set_first_number(int n) { first.store(n == 0 ? 0 : 1, std::memory_order_relaxed); }

int first_number() { return first.load(std::memory_order_relaxed); }

}  // namespace metrica
