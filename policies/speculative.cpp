#include <metrica/policies/speculative.hpp>

#include <fmt/core.h>

namespace metrica {

SpeculativeSettings& Speculative::settings() {
  static SpeculativeSettings s;
  return s;
}

std::string Speculative::describe() {
  const SpeculativeSettings& s = settings();
  if (s.small_list == 0) return fmt::format("speculative on {} threads", threads());
  return fmt::format("speculative on {} threads (lists under {} items on one thread while the mesh is under {} tets)",
                     threads(), s.small_list, 16 * s.small_list);
}

SpeculativeScope::SpeculativeScope(SpeculativeSettings s) : saved_(Speculative::settings()) {
  Speculative::settings() = s;
}

SpeculativeScope::~SpeculativeScope() { Speculative::settings() = saved_; }

}  // namespace metrica
