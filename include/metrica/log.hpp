// Messages for the person running Metrica: warnings and progress.
//
// One process-wide verbosity, set by the command line (-q / -v); library
// code reports through these functions instead of printing directly, so
// that an application embedding Metrica can silence or redirect it.
#pragma once

#include <fmt/core.h>

#include <functional>
#include <string>

namespace metrica::log {

enum class Level { quiet = 0, normal = 1, verbose = 2 };

Level level();
void set_level(Level level);

// Where messages go; defaults to stderr. Replaceable by an embedding
// application (the callback receives the level and the message).
using Sink = std::function<void(Level, const std::string&)>;
void set_sink(Sink sink);

void emit(Level level, const std::string& message);

template <class... Args>
void warn(fmt::format_string<Args...> f, Args&&... args) {
  emit(Level::normal, "warning: " + fmt::format(f, std::forward<Args>(args)...));
}

template <class... Args>
void info(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::verbose) emit(Level::verbose, fmt::format(f, std::forward<Args>(args)...));
}

}  // namespace metrica::log
