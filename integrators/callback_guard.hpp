// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// C callbacks (SUNDIALS right-hand sides, residuals and Jacobians; GSL's) must not let a C++
/// exception cross the C library: the body runs here, an exception is stored for the owner to
/// rethrow after the C call returns, and the library gets its failure code (as deal.II's
/// SUNDIALS wrappers do). Every callback is also where a long step hears SIGINT / SIGTERM under an
/// InterruptGuard (common/interrupt.hpp): it fails with Interrupted, so that a run stops within a
/// callback's time instead of at the end of its step (an IDA step across a tool path's samples
/// can take a minute).
#include <exception>
#include <string>

#include "common/errors.hpp"
#include "common/interrupt.hpp"

namespace roifem::integrators {

/// 0 when `body` returns, `failure` when it throws (the exception kept in `pending`).
template <class Body>
int guarded_callback(std::exception_ptr& pending, int failure, Body&& body) noexcept {
  try {
    if (const int signal_number = InterruptGuard::signal_received())
      throw Interrupted(signal_number, "interrupted by signal " + std::to_string(signal_number) + " inside a step");
    body();
    return 0;
  } catch (...) {
    pending = std::current_exception();
    return failure;
  }
}

}  // namespace roifem::integrators
