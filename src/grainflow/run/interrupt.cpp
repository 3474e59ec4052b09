#include "grainflow/run/interrupt.hpp"

#include <csignal>

namespace grainflow::run {
namespace {

volatile std::sig_atomic_t pending = 0;

extern "C" void note_signal(int signal) { pending = signal; }

}  // namespace

void catch_interrupts() {
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write in progress completes; the loop stops at its next check
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int pending_interrupt() { return pending; }

InterruptScope::InterruptScope() {
  sigaction(SIGINT, nullptr, &saved_int_);
  sigaction(SIGTERM, nullptr, &saved_term_);
  pending = 0;
  catch_interrupts();
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &saved_int_, nullptr);
  sigaction(SIGTERM, &saved_term_, nullptr);
  pending = 0;
}

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

}  // namespace grainflow::run
