// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The DAE formulations of a model with tools (ida_tool_dae.hpp) as integrators of the eliminated
/// system (model/prescribed_motion.hpp): they integrate system.constrained, the same model with the
/// tools' dofs kept and held by multipliers, and report its state in the eliminated numbering, so
/// that `run`, `compare` and every observer take them like any other integrator.
#include <memory>
#include <optional>
#include <vector>

#include "integrators/ida_tool_dae.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"

namespace roifem::integrators {

/// The factory's maker for the table's tool-DAE rows (method_id: the ToolFormulation).
std::unique_ptr<Integrator> make_tool_dae(const IntegratorInfo& info, const StepControl& control);
/// The table's rows of this method: ida-index3, ida-ggl, ida-index1.
std::vector<IntegratorInfo> tool_dae_rows();

class ToolDae final : public Integrator {
 public:
  ToolDae(std::string name, ToolFormulation formulation, StepControl control);
  std::string_view name() const override { return name_; }
  Stats stats() const override;
  std::optional<ConstraintReport> constraints() const override;
  /// A nonlinear model by Newton with the tangent (IDA's setup policy rebuilding it), as ida-bdf5.
  bool takes_nonlinear() const override { return true; }
  /// The DAE itself (its multipliers, drifts), after reset().
  const IdaToolDae& dae() const { return *dae_; }

 private:
  /// InputError for a system without tools (no system.constrained) or a start away from rest.
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  std::string name_;
  ToolFormulation formulation_;
  StepControl control_;
  const model::ConstrainedForm* form_ = nullptr;
  std::unique_ptr<IdaToolDae> dae_;
};

}  // namespace roifem::integrators
