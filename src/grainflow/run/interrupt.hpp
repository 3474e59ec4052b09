// SIGINT and SIGTERM during a run: the handler only notes the signal; the run loop sees it at its
// next step (DEM) or output time (EDMD), writes a checkpoint and every output, and the process exits
// with 128 + the signal's number (130, 143), as a shell reports a process the signal killed.
#pragma once

#include <csignal>

namespace grainflow::run {

void catch_interrupts();  // installs the handlers (idempotent)
int pending_interrupt();  // 0, or the signal's number once one arrived
const char* signal_name(int signal);

// The same handlers for as long as it lives, the ones before it (a Python interpreter's, say) put
// back when it ends; no signal pending at its start.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction saved_int_, saved_term_;
};

}  // namespace grainflow::run
