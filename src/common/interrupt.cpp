#include "common/interrupt.hpp"

namespace roifem {

namespace {
volatile std::sig_atomic_t received = 0;
extern "C" void on_signal(int signal_number) { received = signal_number; }
}  // namespace

InterruptGuard::InterruptGuard() {
  received = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

int InterruptGuard::signal_received() { return received; }

}  // namespace roifem
