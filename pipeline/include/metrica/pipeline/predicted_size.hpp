// What an adaptation is predicted to make, from its metric's complexity,
// and the guard that refuses a run the machine cannot hold before any
// work: the command's --max-tets, Python's max_tets.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace metrica {

// The peak of an adaptation was measured at 110-114 bytes per output tet
// from 4.3M to 108M tets, one and two threads (154-158 at 1M, where the
// program's fixed part weighs more; docs/benchmarks.md, "Memory"); a tenth
// more is kept for meshes that grow more within a cycle.
inline constexpr double kBytesPerTet = 125;
// Output tets per unit of complexity: 10-14 measured on the UGAWG cases.
inline constexpr double kTetsPerComplexity = 10;

// What 90% of this machine's memory holds at kBytesPerTet.
std::size_t default_max_tets();

// "512 B", "1.5 KiB", "12.3 MiB", "1.25 GiB".
std::string bytes_text(double bytes);

struct PredictedSize {
  double complexity = 0, tets = 0, bytes = 0;
};

// The prediction for `complexity`; InputError "{who}: {what} has
// complexity C: about T tets and B of memory; the limit is L tets ({raise})"
// when T exceeds max_tets (0: default_max_tets()). `raise` says how the
// caller's user raises the limit.
PredictedSize check_predicted_size(double complexity, double max_tets, std::string_view who, std::string_view what,
                                   std::string_view raise);

}  // namespace metrica
