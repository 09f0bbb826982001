#include "messages.hpp"

#include <metrica/log.hpp>

#include <mutex>
#include <pybind11/pybind11.h>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace metrica::python {

namespace {

std::mutex g_waiting_mutex;
std::vector<std::pair<log::Level, std::string>> g_waiting;

// With the GIL held. A warning the filters turn into an error (or any
// failure of Python's machinery) cannot be raised from inside the library:
// it is reported as unraisable, as Python does for errors in destructors.
void deliver(log::Level, const std::string& message) {
  try {
    constexpr std::string_view kWarning = "warning: ";
    if (message.rfind(kWarning, 0) == 0) {
      const py::module_ metrica = py::module_::import("metrica");
      const py::object category = py::hasattr(metrica, "MetricaWarning")
                                      ? metrica.attr("MetricaWarning")
                                      : py::reinterpret_borrow<py::object>(PyExc_UserWarning);
      py::module_::import("warnings").attr("warn")(message.substr(kWarning.size()), category);
    } else {
      py::module_::import("logging").attr("getLogger")("metrica").attr("info")(message);
    }
  } catch (py::error_already_set& e) {
    e.discard_as_unraisable("metrica's message");
  }
}

void deliver_waiting() {
  std::vector<std::pair<log::Level, std::string>> waiting;
  {
    std::lock_guard lock(g_waiting_mutex);
    waiting.swap(g_waiting);
  }
  for (const auto& [level, message] : waiting) deliver(level, message);
}

}  // namespace

void route_messages_to_python() {
  log::set_sink([](log::Level level, const std::string& message) {
    if (Py_IsInitialized() && PyGILState_Check()) {
      deliver_waiting();
      deliver(level, message);
    } else {
      std::lock_guard lock(g_waiting_mutex);
      g_waiting.emplace_back(level, message);
    }
  });
}

MessagesDelivered::~MessagesDelivered() {
  if (!PyGILState_Check()) return;
  const py::error_scope unwinding;  // an error on its way to Python stays set
  deliver_waiting();
}

}  // namespace metrica::python
