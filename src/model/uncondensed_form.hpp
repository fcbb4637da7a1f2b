// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where a static condensation came from: the full system and its split into the ROI and the
/// static part, for the integrator that keeps the static part as algebraic unknowns instead of
/// condensing it (integrators/ida_roi_dae.hpp, `ida-roi-dae`).
#include <memory>
#include <vector>

#include "model/internal_force.hpp"
#include "model/second_order_system.hpp"

namespace roifem::model {

struct UncondensedForm {
  /// Not owned: the full model the condensation was built from. Both belong to one model
  /// (simulation::ScenarioModel), which is held in place, so the full system outlives every copy
  /// of the condensed one.
  const SecondOrderSystem* full = nullptr;
  std::vector<Index> roi;          ///< the condensed system's unknown i is full's unknown roi[i]
  std::vector<Index> static_part;  ///< full's other unknowns, ascending
  /// A hybrid ROI (model/hyperelastic_force.hpp): its law on the full model, uncondensed (the
  /// elements with no static node by the law, the others by K); null for a linear model.
  std::shared_ptr<const InternalForce> law;
};

}  // namespace roifem::model
