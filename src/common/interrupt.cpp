// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/interrupt.hpp"

#include <atomic>

namespace roifem {

namespace {
volatile std::sig_atomic_t received = 0;
std::atomic<int> guards{0};  ///< guards alive (a nested one keeps the outer's handlers in previous_*)
extern "C" void on_signal(int signal_number) { received = signal_number; }
}  // namespace

InterruptGuard::InterruptGuard() {
  if (guards++ == 0) received = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
  // A signal heard under the last guard is answered by now: none is pending once it goes (a
  // later integration without a guard must not stop for it).
  if (--guards == 0) received = 0;
}

int InterruptGuard::signal_received() { return guards > 0 ? received : 0; }

}  // namespace roifem
