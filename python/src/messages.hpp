// Metrica's messages (metrica/log.hpp) in Python: a warning through
// warnings.warn (category metrica.MetricaWarning), any other message
// through the "metrica" logger. A message from a thread without the GIL
// (an adaptation releases it; its worker threads never hold it) waits
// until a thread with the GIL delivers it: the next message, or the
// MessagesDelivered guard of the call that released it.
#pragma once

namespace metrica::python {

// Installs the sink (at import).
void route_messages_to_python();

// Delivers the messages waiting, at the end of its scope; constructed with
// the GIL held, before the GIL is released.
class MessagesDelivered {
 public:
  MessagesDelivered() = default;
  MessagesDelivered(const MessagesDelivered&) = delete;
  MessagesDelivered& operator=(const MessagesDelivered&) = delete;
  ~MessagesDelivered();
};

}  // namespace metrica::python
