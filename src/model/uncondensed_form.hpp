// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where a static condensation came from: the full system and its split into the ROI and the
/// static part, for the integrator that keeps the static part as algebraic unknowns instead of
/// condensing it (integrators/ida_roi_dae.hpp, `ida-roi-dae`).
#include <vector>

#include "model/second_order_system.hpp"

namespace roifem::model {

struct UncondensedForm {
  /// Not owned: the full model the condensation was built from. Both belong to one model
  /// (simulation::ScenarioModel), which is held in place, so the full system outlives every copy
  /// of the condensed one.
  const SecondOrderSystem* full = nullptr;
  std::vector<Index> roi;          ///< the condensed system's unknown i is full's unknown roi[i]
  std::vector<Index> static_part;  ///< full's other unknowns, ascending
};

}  // namespace roifem::model
