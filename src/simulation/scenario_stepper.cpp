#include "simulation/scenario_stepper.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "io/csv.hpp"

namespace roifem::simulation {

ScenarioStepper::ScenarioStepper(const scenario::Scenario& scenario, bool energy)
    : scenario_(scenario),
      integrator_(scenario_integrator(scenario_)),  // an unknown name fails before any work
      state_() {
  model_ = build_scenario_model(scenario_);
  state_ = model::State::at_rest(model_->system().size());
  integrator_->reset(model_->system(), state_);
  t0_ = state_.t;
  if (energy) ledger_.emplace(model_->system(), state_, &model_->tools);
  roi_components_ = model_->roi_components();
}

void ScenarioStepper::step() {
  const double* u_storage = state_.u.data();
  const double* v_storage = state_.v.data();
  integrator_->advance_to(next_time(), state_);
  ++k_;
  // Views of u and v (the Python module's) rely on this.
  if (state_.u.data() != u_storage || state_.v.data() != v_storage)
    throw Error(scenario_.integrator + ": the state's storage moved during a step (a bug in the integrator)");
  if (!state_.u.allFinite())
    throw SolverError(
        io::format("%s: non-finite displacement at step %ld, t = %g s", scenario_.integrator.c_str(), k_, state_.t));
  if (ledger_) ledger_->record(state_);
}

long ScenarioStepper::step_to(double t) {
  long taken = 0;
  while (next_time() <= t + 1e-9 * scenario_.dt) {
    step();
    ++taken;
  }
  return taken;
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
  if (!reactions_) reactions_ = std::make_unique<model::ReactionForces>(model_->full);
  return *reactions_;
}

Vector ScenarioStepper::reaction_forces() { return reactions().nodal(displacement()); }

Vector ScenarioStepper::tool_forces() const { return model_->tools.forces(state_.u, state_.t); }

}  // namespace roifem::simulation
