// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The uncondensed ROI DAE (ida_roi_dae.hpp) as an integrator of a statically condensed system:
/// it integrates system.uncondensed, the full model with the static part kept as algebraic
/// unknowns, and reports the ROI's state in the condensed numbering, so that `run`, `compare` and
/// every observer (tools' forces, energies) take it like any other integrator. Its trajectory is
/// the condensed model's to the tolerance: condensation eliminates exactly the static part.
#include <memory>
#include <vector>

#include "integrators/ida_roi_dae.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"

namespace roifem::integrators {

/// The factory's maker for the table's `ida-roi-dae` row.
std::unique_ptr<Integrator> make_roi_dae(const IntegratorInfo& info, const StepControl& control);
/// The table's row of this method: ida-roi-dae.
std::vector<IntegratorInfo> roi_dae_rows();

class RoiDae final : public Integrator {
 public:
  explicit RoiDae(StepControl control);
  std::string_view name() const override { return "ida-roi-dae"; }
  Stats stats() const override;
  /// A hybrid ROI by Newton on its law uncondensed (model::UncondensedForm::law).
  bool takes_nonlinear() const override { return true; }

 private:
  /// InputError for a system that is not a static condensation (no system.uncondensed) or a
  /// start away from rest.
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  StepControl control_;
  std::unique_ptr<IdaRoiDae> dae_;
  Vector u_d_, u_s_;
};

}  // namespace roifem::integrators
