// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// SIGINT and SIGTERM as a request the time loop honours between two steps, so that a run stops
/// with its results file closed, valid and marked incomplete instead of dying mid-write.
/// Signals belong to the process: the flag the handler sets (a std::sig_atomic_t) and the count of
/// guards alive are the one piece of process-wide state in roifem, kept by this class alone. A
/// signal counts only while a guard is alive: a request heard under one is gone with the last.
#include <csignal>

namespace roifem {

class InterruptGuard {
 public:
  /// Installs the handlers and clears any earlier request.
  InterruptGuard();
  /// Restores the handlers that were there before.
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// The signal received since the guard was installed (0: none).
  static int signal_received();

 private:
  struct sigaction previous_int_ {
  }, previous_term_{};
};

}  // namespace roifem
