// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// An explicit method at a fixed step on a nonlinear model: its stability limit moves with the
/// tangent, so it is estimated from the tangent at the current state (TLED's and NiftySim's way
/// on explicit central differences): after each output, the highest frequency of M u'' + K_t(u) u
/// (model::highest_frequency, Lanczos on the tangent) gives the method's limit by its Butcher
/// table's stability function with the model's damping (integrators/stability.hpp). A step beyond
/// it is refused there, naming the time, the step, the frequency and the limit, before it can
/// diverge. The factory attaches one to every explicit fixed-step method with a tableau, unless
/// StepControl::watch_stability is off (compare's own stability search steps past the limit on
/// purpose).
#include <limits>
#include <string_view>
#include <utility>

#include "integrators/integrator_info.hpp"
#include "model/second_order_system.hpp"

namespace roifem::integrators {

class StabilityWatch {
 public:
  StabilityWatch(IntegratorInfo method, double dt) : method_(std::move(method)), dt_(dt) {}
  /// After an output at `state` (a nonlinear system only; a linear one's limit does not move):
  /// SolverError when the step is beyond the limit the tangent there gives. `steps`: the method's
  /// steps so far, for the message.
  void check(std::string_view name, const model::SecondOrderSystem& system, const model::State& state, long steps);
  /// The smallest limit found so far (s; infinity before the first check).
  double smallest_limit() const { return smallest_limit_; }

 private:
  IntegratorInfo method_;
  double dt_;
  double smallest_limit_ = std::numeric_limits<double>::infinity();
  double alpha_ = 0;  ///< the model's mass-proportional damping (1/s), read at the first check
  SparseMatrix K_t_;
  Vector f_;
};

}  // namespace roifem::integrators
