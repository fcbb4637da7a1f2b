// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/tool_dae.hpp"

#include "common/errors.hpp"
#include "integrators/integrator_info.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_tool_dae(const IntegratorInfo& info, const StepControl& control) {
  return std::make_unique<ToolDae>(info.name, static_cast<ToolFormulation>(info.method_id), control);
}

ToolDae::ToolDae(std::string name, ToolFormulation formulation, StepControl control)
    : name_(std::move(name)), formulation_(formulation), control_(control) {
  if (!(control_.rtol > 0 && control_.atol > 0)) throw InputError(name_ + ": tolerances rtol and atol must be positive");
}

void ToolDae::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  if (!system.constrained)
    throw InputError(name_ + " integrates a model with tools ([[tool]]) as a constrained DAE, and this one has " +
                     (system.modal ? "its tools eliminated by a reduction whose basis is learnt from the eliminated model's "
                                     "loads (POD): the tool-kept model would learn another; use craig-bampton"
                                   : "none: choose an integrator of the plain equations (ida-bdf5)"));
  if (initial.u.squaredNorm() != 0 || initial.v.squaredNorm() != 0)
    throw InputError(name_ + ": starts at rest only (the tools' nodes on their paths)");
  form_ = system.constrained.get();
  if (system.is_nonlinear() != form_->all.is_nonlinear())
    throw Error("internal: " + name_ + ": the tools' DAE form and the model differ in their law");
  dae_ = std::make_unique<IdaToolDae>(form_->all, form_->tools, formulation_, control_);
  dae_->reset(initial.t);
}

void ToolDae::advance(double t_out, model::State& state) {
  dae_->advance_to(t_out);
  const Vector u = dae_->displacement(), v = dae_->velocity();
  for (std::size_t i = 0; i < form_->kept.size(); ++i) {
    state.u[static_cast<Index>(i)] = u[form_->kept[i]];
    state.v[static_cast<Index>(i)] = v[form_->kept[i]];
  }
  state.t = dae_->t();
}

std::optional<ConstraintReport> ToolDae::constraints() const {
  if (!dae_) return std::nullopt;
  return ConstraintReport{
      .forces = dae_->tool_forces(), .position_drift = dae_->position_drift(), .velocity_drift = dae_->velocity_drift()};
}

Stats ToolDae::stats() const { return dae_ ? dae_->stats() : Stats{}; }

std::vector<IntegratorInfo> tool_dae_rows() {
  auto row = [](const char* name, ToolFormulation formulation, const char* summary) {
    return IntegratorInfo{.name = name,
                          .family = Family::ida,
                          .order = 5,
                          .adaptive = true,
                          .linear_solver = LinearSolver::klu,
                          .method_id = static_cast<int>(formulation),
                          .make = make_tool_dae,
                          .summary = summary,
                          .needs_tools = true,
                          .nonlinear = true};
  };
  return {row("ida-index3", ToolFormulation::index3,
              "IDA on the tools' DAE, index 3 (position constraints; velocities and multipliers out of the error test), KLU"),
          row("ida-ggl", ToolFormulation::ggl,
              "IDA on the tools' DAE, GGL-stabilized index 2 (position and velocity constraints), KLU"),
          row("ida-index1", ToolFormulation::index1,
              "IDA on the tools' DAE, index 1 (acceleration constraint, Baumgarte-stabilized, a = 100/s), KLU")};
}

}  // namespace roifem::integrators
