// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// C callbacks (SUNDIALS right-hand sides, residuals and Jacobians; GSL's) must not let a C++
/// exception cross the C library: the body runs here, an exception is stored for the owner to
/// rethrow after the C call returns, and the library gets its failure code (as deal.II's
/// SUNDIALS wrappers do). Every callback is also where a long step hears SIGINT / SIGTERM under an
/// InterruptGuard (common/interrupt.hpp): it fails with Interrupted, so that a run stops within a
/// callback's time instead of at the end of its step (an IDA step across a tool path's samples
/// can take a minute).
#include <chrono>
#include <exception>
#include <optional>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"

namespace roifem::integrators {

/// The wall-clock limit of the advance_to running on this thread (Integrator::set_time_limit), heard
/// in every callback as a signal is: a library's one call can take many steps, and GSL's implicit
/// Gauss-Legendre overran a limit fivefold within one output interval (docs/design-figures.md). Set for the span of an
/// advance_to by a TimeLimitScope; none outside one.
class TimeLimitScope {
 public:
  using Clock = std::chrono::steady_clock;
  TimeLimitScope(std::optional<Clock::time_point> deadline, std::string method)
      : previous_(std::exchange(current(), Limit{deadline, std::move(method)})) {}
  ~TimeLimitScope() { current() = std::move(previous_); }
  TimeLimitScope(const TimeLimitScope&) = delete;
  TimeLimitScope& operator=(const TimeLimitScope&) = delete;
  /// OverTime, at model time `t`, when the running advance_to's limit has passed.
  static void check(double t) {
    const Limit& limit = current();
    if (limit.deadline && Clock::now() > *limit.deadline)
      throw OverTime(t, limit.method + ": stopped at t = " + number_text(t) + " s, over its wall-clock limit");
  }

 private:
  struct Limit {
    std::optional<Clock::time_point> deadline;
    std::string method;
  };
  static Limit& current() {
    thread_local Limit limit;
    return limit;
  }
  Limit previous_;
};

/// Interrupted on a signal heard under an InterruptGuard, OverTime past the running advance_to's
/// limit: what a callback and a stepper's own loop check before each piece of work.
inline void stop_if_asked(double t) {
  if (const int signal_number = InterruptGuard::signal_received())
    throw Interrupted(signal_number, "interrupted by signal " + std::to_string(signal_number) + " inside a step");
  TimeLimitScope::check(t);
}

/// 0 when `body` returns, `failure` when it throws (the exception kept in `pending`). `t`: the
/// model time the library asks at, for a time limit's report.
template <class Body>
int guarded_callback(std::exception_ptr& pending, int failure, Body&& body, double t = 0) noexcept {
  try {
    stop_if_asked(t);
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
int guarded_recoverable_callback(std::exception_ptr& pending, std::string& inadmissible, int failure, Body&& body,
                                 double t = 0) noexcept {
  const int flag = guarded_callback(pending, failure, std::forward<Body>(body), t);
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
