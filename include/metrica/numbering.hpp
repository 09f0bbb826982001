// How messages number vertices, tets and triangles: from 1 as libMeshb
// files and the command do (the default), or from 0 as numpy rows do (the
// Python module chooses 0 when imported). Ids stay 0-based; only the
// numbers shown to the user move.
#pragma once

#include <cstddef>

namespace metrica {

// 0 or 1; anything else is taken as 1.
void set_first_number(int first);
int first_number();

// The number a message shows for the entity of index `i`.
inline std::size_t numbered(std::size_t i) { return i + static_cast<std::size_t>(first_number()); }

}  // namespace metrica
