// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A scenario's model advanced step by step by a program that drives it (the Python module):
/// the same model, integrator, time grid t_k = t_0 + k dt and energy ledger as `roifem run`, so
/// that its states equal the run's bit for bit, without the results file. Between steps the caller
/// reads the state (u and v keep their storage for the stepper's life: views of them stay valid),
/// the ROI displacement, the whole field, the energies, the supports' reactions and the tools' forces.
/// A scenario's cuts take effect at the start of the step during which a blade reaches their
/// tetrahedra (simulation/cuts/scenario_cuts.hpp): the system changes in place, the integrator takes
/// the change, the ledger books what was removed, and each listener hears of it.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "integrators/integrator.hpp"
#include "model/energy.hpp"
#include "model/reaction_forces.hpp"
#include "scenario/scenario.hpp"
#include "simulation/cuts/scenario_cuts.hpp"
#include "simulation/run_checkpoint.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

class ScenarioStepper final : public Stepper {
 public:
  /// Builds the scenario's model and integrator (InputError / ModelError as `roifem run`), at rest
  /// at t = 0. `energy`: keep the energy ledger (one product with K and M per step).
  explicit ScenarioStepper(const scenario::Scenario& scenario, bool energy = true);

  /// One step of the scenario's grid: to t_{k+1}. SolverError, naming the integrator, the step and
  /// t, on failure or divergence (integrator.hpp); the state is then that of the failed attempt.
  void step() override;
  /// Steps along the grid to its last point t_k <= t (to within 1e-9 dt): returns the steps taken.
  /// InputError for a t that is not finite or not ahead of the current time.
  long step_to(double t);
  /// The steps step_to(t) takes (the same checks), for a driver that steps them itself.
  long steps_to(double t) const;

  const scenario::Scenario& scenario() const { return scenario_; }
  const ScenarioModel& model() const { return *model_; }
  /// The model to expand a state on (a reduced model's recovery of its static part is not const).
  ScenarioModel& model() { return *model_; }
  const integrators::Integrator& integrator() const { return *integrator_; }
  const model::State& state() const override { return state_; }
  long steps_taken() const override { return k_; }
  /// The integrator's counters, with those of runs it restarted at a cut.
  integrators::Stats stats() const override;
  /// Called at each cut with what it removed and the state it took effect at (the step's start),
  /// before the step goes on; the stepper's own ledger has booked it already.
  using CutListener = std::function<void(const CutEvent& event, const model::State& at_cut)>;
  void on_cut(CutListener listener) { cut_listeners_.push_back(std::move(listener)); }
  /// The cuts' schedule and which tetrahedra remain.
  const ScenarioCuts& cuts() const { return cuts_; }
  /// The grid's next time t_{k+1}.
  double next_time() const { return grid_.at(k_ + 1); }
  /// The ledger; nullptr without energy bookkeeping.
  const model::EnergyLedger* energy() const { return ledger_ ? &*ledger_ : nullptr; }

  /// The run's restart point at this step (run_checkpoint.hpp), with the sums of `ledger` (the
  /// results' ledger; the stepper's own where it keeps one).
  RunCheckpoint checkpoint(const model::EnergyLedger& ledger) const;
  /// Goes on from `saved`, a checkpoint of a run of this scenario, from rest: replays the cuts due
  /// up to its step (each heard by the cut listeners, as in the run), calling `replayed(j)` for each
  /// step j = 0..K where the run recorded it (after that step's cuts); then the state, the
  /// integrator (exactly where it keeps checkpoints, else afresh from the state:
  /// Integrator::resume) and the stepper's own ledger are the checkpoint's. Returns whether the
  /// integrator goes on exactly.
  bool resume(const RunCheckpoint& saved, const std::function<void(long step)>& replayed);

  /// The ROI nodes' displacement in mm, #ROI x 3 row-major, computed as `roifem run` records it
  /// (zero at a fixed component). Empty for the full model.
  std::vector<double> roi_displacement_mm() const;
  /// Every node's displacement (3N, m): the static part recovered, tools on their paths.
  Vector displacement();
  /// The supports' reactions on the tissue (3 per fixed node, N; nodes: reactions().nodes()).
  const model::ReactionForces& reactions();
  Vector reaction_forces();
  /// Each tool's force on the tissue (3 per tool, N).
  Vector tool_forces() const;

 private:
  scenario::Scenario scenario_;
  std::unique_ptr<ScenarioModel> model_;
  std::unique_ptr<integrators::Integrator> integrator_;
  model::State state_;
  model::TimeGrid grid_;  ///< t_k = t_0 + k dt from rest at t_0
  long k_ = 0;
  std::optional<model::EnergyLedger> ledger_;
  std::vector<Index> roi_components_;                 ///< each ROI node's components among the unknowns (-1: fixed)
  std::unique_ptr<model::ReactionForces> reactions_;  ///< made on first use
  ScenarioCuts cuts_;
  std::vector<CutListener> cut_listeners_;
  integrators::Stats restarted_;  ///< counters of the integrator's runs before its restarts at cuts
  void cut_due(double t);
};

}  // namespace roifem::simulation
