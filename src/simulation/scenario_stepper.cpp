// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_stepper.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"

namespace roifem::simulation {

ScenarioStepper::ScenarioStepper(const scenario::Scenario& scenario, bool energy)
    : scenario_(scenario),
      integrator_(scenario_integrator(scenario_)),  // an unknown name fails before any work
      state_(),
      grid_(0.0, scenario_.dt, scenario_.integrator) {
  model_ = build_scenario_model(scenario_);
  cuts_ = ScenarioCuts(scenario_, *model_);
  state_ = model::State::at_rest(model_->system().size(), grid_.t0());
  integrator_->reset(model_->system(), state_);
  if (energy) ledger_.emplace(model_->system(), state_, &model_->tools);
  roi_components_ = model_->roi_components();
}

void ScenarioStepper::cut_due(double t) {
  const CutEvent event = cuts_.cut_due(t, *model_, state_);
  const integrators::Stats before = integrator_->stats();
  if (!event.change.dofs.empty() && integrator_->take_change(model_->system(), event.change, state_)) restarted_ += before;
  if (ledger_) ledger_->account_cut(state_, event.energy_removed());
  reactions_.reset();  // the supports' rows of K change with the mesh
  for (const auto& listener : cut_listeners_) listener(event, state_);
}

integrators::Stats ScenarioStepper::stats() const {
  integrators::Stats total = restarted_;
  total += integrator_->stats();
  return total;
}

void ScenarioStepper::step() {
  if (cuts_.due(next_time())) cut_due(next_time());
  integrator_->advance_to(next_time(), state_);
  ++k_;  // the seam (Integrator::advance_to) keeps u and v where they are: the Python module's views rely on it
  if (ledger_) ledger_->record(state_);
}

RunCheckpoint ScenarioStepper::checkpoint(const model::EnergyLedger& ledger) const {
  return {.step = k_, .state = state_, .integrator = integrator_->checkpoint(), .restarted = restarted_, .ledger = ledger.sums()};
}

bool ScenarioStepper::resume(const RunCheckpoint& saved, const std::function<void(long step)>& replayed) {
  if (k_ != 0) throw Error("internal: a restart resumes a stepper at rest, not at step " + std::to_string(k_));
  if (saved.state.u.size() != state_.u.size())
    throw InputError(format("%s: the restart point has %lld unknowns where this scenario's model has %lld",
                            scenario_.file.c_str(), static_cast<long long>(saved.state.u.size()),
                            static_cast<long long>(state_.u.size())));
  // The cuts up to the restart point, on the model and the integrator, in the run's order: the
  // factor takes the same corrections (a cut's change does not depend on the state; what the
  // state gives the integrator and the ledger is replaced by the checkpoint's below).
  replayed(0);
  for (long j = 1; j <= saved.step; ++j) {
    if (cuts_.due(grid_.at(j))) {
      k_ = j - 1;  // the listeners hear the cut at the start of step j, as in the run
      state_.t = grid_.at(j - 1);
      cut_due(grid_.at(j));
    }
    replayed(j);
  }
  state_.u = saved.state.u;
  state_.v = saved.state.v;
  state_.t = saved.state.t;
  k_ = saved.step;
  restarted_ = saved.restarted;
  try {
    integrator_->resume(model_->system(), state_, saved.integrator);
  } catch (const InputError& e) {
    throw InputError(format("%s: a restart at step %ld (t = %s s): %s; restart with another integrator", scenario_.file.c_str(),
                            saved.step, number_text(saved.state.t).c_str(), e.what()));
  }
  if (ledger_) ledger_->resume(state_, saved.ledger);
  reactions_.reset();
  return saved.integrator.has_value() && integrator_->restarts_exactly();
}

long ScenarioStepper::steps_to(double t) const {
  if (!std::isfinite(t)) throw InputError(format("step_to: t = %g s is not a time to step to", t));
  if (t <= state_.t)
    throw InputError(
        format("step_to: t = %.9g s is not ahead of the simulation, which is at t = %.9g s (step %ld)", t, state_.t, k_));
  // The last grid point t_k <= t (to within 1e-9 dt), counted without stepping there.
  const double k = std::floor((t - grid_.t0()) / grid_.dt() + 1e-9);
  if (k > 1e15)
    throw InputError(format("step_to: t = %g s is %.3g steps of dt = %g s away", t, k - static_cast<double>(k_), grid_.dt()));
  return grid_.last_at_or_before(t) - k_;
}

long ScenarioStepper::step_to(double t) {
  const long steps = steps_to(t);
  for (long k = 0; k < steps; ++k) step();
  return steps;
}

std::vector<double> ScenarioStepper::roi_displacement_mm() const {
  std::vector<double> out(roi_components_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = roi_components_[i] < 0 ? 0.0 : state_.u[roi_components_[i]] / mm;
  return out;
}

Vector ScenarioStepper::displacement() {
  const Vector u_free = model_->condensation ? model_->condensation->expand(state_.u, state_.t) : state_.u;
  return model_->full.displacement(u_free, state_.t);
}

const model::ReactionForces& ScenarioStepper::reactions() {
  if (!reactions_) reactions_ = std::make_unique<model::ReactionForces>(model_->full, cuts_.still_there());
  return *reactions_;
}

Vector ScenarioStepper::reaction_forces() { return reactions().nodal(displacement()); }

Vector ScenarioStepper::tool_forces() const { return model_->tools.forces(state_.u, state_.t); }

}  // namespace roifem::simulation
