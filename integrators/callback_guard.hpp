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
#include <utility>

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

/// As guarded_callback, for a callback whose library can retry with a smaller step: a ModelError
/// (a state the model does not admit, such as a Newton iterate that inverts an element) returns 1,
/// recoverable, and its message is kept in `inadmissible` for the report should the library give
/// up. A linear model never throws one.
template <class Body>
int guarded_recoverable_callback(std::exception_ptr& pending, std::string& inadmissible, int failure, Body&& body) noexcept {
  const int flag = guarded_callback(pending, failure, std::forward<Body>(body));
  if (flag == 0) return 0;
  try {
    std::rethrow_exception(pending);
  } catch (const ModelError& e) {
    inadmissible = e.what();
    pending = nullptr;
    return 1;
  } catch (...) {
  }
  return flag;
}

}  // namespace roifem::integrators
