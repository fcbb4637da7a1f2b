// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/run_loop.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/errors.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "simulation/progress.hpp"

namespace roifem::simulation {

RunSummary run(Stepper& stepper, long steps, const std::vector<StepObserver>& observers, const std::string& progress_label,
               std::ostream* progress_log) {
  if (steps <= 0) throw InputError("number of steps " + std::to_string(steps) + " must be positive");
  RunSummary summary;
  // Grows as it goes beyond a million steps: a run stopped early never holds a huge reservation.
  summary.step_seconds.reserve(static_cast<std::size_t>(std::min(steps, 1L << 20)));
  std::unique_ptr<ProgressReporter> progress;
  if (!progress_label.empty()) progress = std::make_unique<ProgressReporter>(progress_label, steps, 2.0, "steps", progress_log);
  for (long k = 1; k <= steps; ++k) {
    Stopwatch clock;
    const double from = stepper.state().t;
    try {
      stepper.step();
    } catch (const Interrupted& e) {  // heard inside the step (integrators/callback_guard.hpp)
      throw Interrupted(e.signal, "interrupted by signal " + std::to_string(e.signal) + " during step " + std::to_string(k) +
                                      " of " + std::to_string(steps) + " (from t = " + number_text(from) + " s)");
    }
    const double seconds = clock.seconds();
    summary.step_seconds.push_back(seconds);
    summary.steps = k;
    const model::State& state = stepper.state();
    for (const auto& observe : observers) observe(k, state, seconds);
    if (progress) progress->update(k);
    if (const int signal_number = InterruptGuard::signal_received())
      throw Interrupted(signal_number, "interrupted by signal " + std::to_string(signal_number) + " after step " +
                                           std::to_string(k) + " of " + std::to_string(steps) +
                                           " (t = " + std::to_string(state.t) + " s)");
  }
  summary.stats = stepper.stats();
  return summary;
}

RunSummary run(integrators::Integrator& integrator, model::State& state, double dt, long steps,
               const std::vector<StepObserver>& observers, const std::string& progress_label, std::ostream* progress_log) {
  GridStepper stepper(integrator, state, dt);
  return run(stepper, steps, observers, progress_label, progress_log);
}

double median(std::vector<double> values) { return percentile(std::move(values), 0.5); }

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::lround(p * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace roifem::simulation
