// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The time loop: advances an integrator over the grid t_k = t_0 + k dt, k = 1..steps, timing each
/// step, and hands every state to the observers (output, energy, error live there, never in an
/// integrator). Throws SolverError from the integrator unchanged; observers keep what they saw.
/// Under an InterruptGuard, a SIGINT / SIGTERM stops it after the step in progress (Interrupted).
#include <functional>
#include <vector>

#include "integrators/integrator.hpp"

namespace roifem::simulation {

/// Called after every step k (1-based) with the new state and the step's wall time.
using StepObserver = std::function<void(long step, const model::State& state, double step_seconds)>;

struct RunSummary {
  long steps = 0;
  std::vector<double> step_seconds;
  integrators::Stats stats;
};

/// The integrator must be reset() to `state` already.
RunSummary run(integrators::Integrator& integrator, model::State& state, double dt, long steps,
               const std::vector<StepObserver>& observers, const std::string& progress_label = "");

/// Median and 99th percentile of step times (s).
double median(std::vector<double> values);
double percentile(std::vector<double> values, double p);

}  // namespace roifem::simulation
