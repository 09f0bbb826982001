// The unit band: an edge conforms to the metric when its metric length is
// in [1/sqrt 2, sqrt 2] (UGAWG). Splits take edges above it, collapses
// edges below it, and the reports count the share inside it.
#pragma once

#include <cmath>

namespace metrica {

struct UnitBand {
  double lo, hi;
  bool contains(double length) const { return length >= lo && length <= hi; }
};

inline const UnitBand kUnitBand{1.0 / std::sqrt(2.0), std::sqrt(2.0)};

}  // namespace metrica
