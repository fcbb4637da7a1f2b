// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// How an integrator chooses its steps: a fixed dt, or error-controlled steps with rtol / atol.
/// Its own header, so that a client of the factory includes no library's headers.

namespace roifem::integrators {

struct StepControl {
  double dt = 0.05;       ///< fixed step, or the first step / output interval when adaptive
  bool adaptive = false;  ///< error-controlled steps with rtol / atol
  double rtol = 1e-6, atol = 1e-9;
  /// An explicit method at a fixed step on a nonlinear model: refuse a step beyond the stability
  /// limit the tangent gives after each output (integrators/stability_watch.hpp). Off only where
  /// steps past the limit are the point (compare's own stability search).
  bool watch_stability = true;
};

}  // namespace roifem::integrators
