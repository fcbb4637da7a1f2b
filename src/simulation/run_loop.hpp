// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The time loop: advances a stepper over its grid t_k = t_0 + k dt (model/time_grid.hpp), k =
/// 1..steps, timing each step, and hands every state to the observers (output, energy, error live
/// there, never in an integrator). Throws SolverError from the integrator unchanged; observers keep
/// what they saw. Under an InterruptGuard, a SIGINT / SIGTERM stops it after the step in progress,
/// or inside it (Interrupted, naming the step).
/// One path: `roifem run` steps a ScenarioStepper through run(), as the Python module steps the same
/// stepper one step at a time; the paper experiment steps an integrator on a grid (GridStepper).
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "model/time_grid.hpp"

namespace roifem::simulation {

/// Called after every step k (1-based) with the new state and the step's wall time.
using StepObserver = std::function<void(long step, const model::State& state, double step_seconds)>;

/// What takes one step at a time along its grid.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// One step: to t_{k+1}. SolverError or Interrupted as Integrator::advance_to.
  virtual void step() = 0;
  virtual const model::State& state() const = 0;
  virtual long steps_taken() const = 0;
  virtual integrators::Stats stats() const = 0;
};

/// An integrator stepping a state along the grid from the state's time.
class GridStepper final : public Stepper {
 public:
  /// The integrator must be reset() to `state` already; both must outlive the stepper.
  GridStepper(integrators::Integrator& integrator, model::State& state, double dt)
      : integrator_(integrator), state_(state), grid_(state.t, dt, integrator.name()) {}
  void step() override {
    integrator_.advance_to(grid_.at(k_ + 1), state_);
    ++k_;
  }
  const model::State& state() const override { return state_; }
  long steps_taken() const override { return k_; }
  integrators::Stats stats() const override { return integrator_.stats(); }

 private:
  integrators::Integrator& integrator_;
  model::State& state_;
  model::TimeGrid grid_;
  long k_ = 0;
};

struct RunSummary {
  long steps = 0;
  std::vector<double> step_seconds;
  integrators::Stats stats;
};

/// `progress_label`: a terminal's progress line (progress.hpp); `progress_log`: where its
/// logged lines go, terminal or not (none: only the terminal's).
RunSummary run(Stepper& stepper, long steps, const std::vector<StepObserver>& observers, const std::string& progress_label = "",
               std::ostream* progress_log = nullptr);
/// An integrator (reset to `state` already) on the grid from state.t with step dt.
RunSummary run(integrators::Integrator& integrator, model::State& state, double dt, long steps,
               const std::vector<StepObserver>& observers, const std::string& progress_label = "",
               std::ostream* progress_log = nullptr);

/// Median and 99th percentile of step times (s).
double median(std::vector<double> values);
double percentile(std::vector<double> values, double p);

}  // namespace roifem::simulation
