// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/roi_dae.hpp"

#include "common/errors.hpp"
#include "integrators/integrator_info.hpp"
#include "model/uncondensed_form.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_roi_dae(const IntegratorInfo&, const StepControl& control) {
  return std::make_unique<RoiDae>(control);
}

RoiDae::RoiDae(StepControl control) : control_(control) {
  if (!(control_.rtol > 0 && control_.atol > 0)) throw InputError("ida-roi-dae: tolerances rtol and atol must be positive");
}

void RoiDae::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  if (!system.uncondensed)
    throw InputError(
        "ida-roi-dae integrates an ROI model with its static part kept as algebraic unknowns: it needs a scenario with "
        "an [roi] reduced by static condensation (reduction = \"static\")");
  if (initial.u.squaredNorm() != 0 || initial.v.squaredNorm() != 0)
    throw InputError("ida-roi-dae: starts at rest only (IDA makes the static part consistent)");
  const model::UncondensedForm& form = *system.uncondensed;
  roi::Partition partition;
  partition.d = form.roi;
  partition.s = form.static_part;
  if (system.is_nonlinear() && !form.law)
    throw Error("internal: ida-roi-dae: a nonlinear ROI model whose uncondensed form has no law");
  dae_ = std::make_unique<IdaRoiDae>(*form.full, partition, control_, 5, system.is_nonlinear() ? form.law : nullptr);
  dae_->reset(initial.t);
}

void RoiDae::advance(double t_out, model::State& state) {
  dae_->advance_to(t_out, u_d_, u_s_);
  state.u = u_d_;
  state.v = dae_->velocity_d();
  state.t = dae_->t();
}

Stats RoiDae::stats() const { return dae_ ? dae_->stats() : Stats{}; }

std::vector<IntegratorInfo> roi_dae_rows() {
  return {{.name = "ida-roi-dae",
           .family = Family::ida,
           .order = 5,
           .adaptive = true,
           .linear_solver = LinearSolver::klu,
           .method_id = 5,
           .make = make_roi_dae,
           .summary = "IDA on the ROI model uncondensed: the static part kept as algebraic unknowns "
                      "(scenarios with an [roi] and static condensation; tools eliminated), KLU",
           .needs_uncondensed = true,
           .nonlinear = true}};
}

}  // namespace roifem::integrators
