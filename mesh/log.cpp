#include <metrica/log.hpp>

#include <atomic>
#include <cstdio>
#include <mutex>

namespace metrica::log {
namespace {
std::atomic<Level> g_level{Level::normal};
std::mutex g_sink_mutex;
Sink g_sink;
}  // namespace

Level level() { return g_level.load(std::memory_order_relaxed); }
void set_level(Level lvl) { g_level.store(lvl, std::memory_order_relaxed); }

void set_sink(Sink sink) {
  std::lock_guard lock(g_sink_mutex);
  g_sink = std::move(sink);
}

void emit(Level lvl, const std::string& message) {
  if (lvl > level()) return;
  std::lock_guard lock(g_sink_mutex);
  if (g_sink) {
    g_sink(lvl, message);
  } else {
    std::fprintf(stderr, "%s\n", message.c_str());
  }
}

}  // namespace metrica::log
