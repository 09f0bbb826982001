#include <metrica/error.hpp>
#include <metrica/pipeline/predicted_size.hpp>

#include <fmt/core.h>

#include <unistd.h>

namespace metrica {

std::size_t default_max_tets() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 100'000'000;
  return static_cast<std::size_t>(0.9 * double(pages) * double(page) / kBytesPerTet);
}

std::string bytes_text(double bytes) {
  if (bytes < 1024) return fmt::format("{:.0f} B", bytes);
  if (bytes < 1024.0 * 1024) return fmt::format("{:.1f} KiB", bytes / 1024);
  if (bytes < 1024.0 * 1024 * 1024) return fmt::format("{:.1f} MiB", bytes / (1024.0 * 1024));
  return fmt::format("{:.3g} GiB", bytes / (1024.0 * 1024 * 1024));
}

PredictedSize check_predicted_size(double complexity, double max_tets, std::string_view who, std::string_view what,
                                   std::string_view raise) {
  const double limit = max_tets > 0 ? max_tets : double(default_max_tets());
  const PredictedSize p{complexity, kTetsPerComplexity * complexity, kTetsPerComplexity * complexity * kBytesPerTet};
  if (!(p.tets <= limit))
    throw InputError(
        fmt::format("{}: {} has complexity {:.4g}: about {:.3g} tets and {} of memory; the limit is "
                    "{:.3g} tets ({})",
                    who, what, complexity, p.tets, bytes_text(p.bytes), limit, raise));
  return p;
}

}  // namespace metrica
