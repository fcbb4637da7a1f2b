// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem run`: one scenario, full or condensed, integrated and written to DIR/results.h5 and
/// DIR/results.xdmf. results.h5 holds (lengths in mm, energies in J):
///   /mesh/nodes_mm (N x 3), /mesh/tets (E x 4; E x 10 with element = "tet10")
///   /time_s (K+1), /step_wall_time_s (K+1, 0 at t_0)
///   /energy/{kinetic_J, strain_J, dissipated_J, external_work_J} (K+1), tool_work_J with tools
///   /tools/NAME/{nodes, displacement_mm (K+1 x 3), force_N (K+1 x 3)}   (with [[tool]]s; the
///       force the tool applies to the tissue, summed over its nodes: the surgeon feels -force_N)
///   /tools/NAME/multiplier_force_N (K+1 x 3), /tools/position_drift_mm (K+1)  (DAE forms: from
///       the multipliers, and the constraint's drift)
///   /roi/nodes (R), /roi/displacement_mm (K+1 x R x 3)             (with an ROI)
///   /fields/displacement_mm_NNNNNN (N x 3) every output.field_every steps, static part recovered
///   /energy/cut_J, /cuts/{removed_elements, removed_at_step, removed_at_s}, /mesh/tets_from_step_NNNNNN
///       (with [[cut]]s: the energy they took, what they removed and when, the tetrahedra left)
///   attributes: scenario (the resolved TOML), integrator, counters, status
/// Series are extendible, chunked, Fletcher32-checksummed datasets appended step by step.
#include <filesystem>
#include <iosfwd>

#include "integrators/integrator.hpp"
#include "scenario/scenario.hpp"

namespace roifem::simulation {

struct ScenarioRunSummary {
  Index dofs = 0, roi_nodes = 0;
  long steps = 0;
  double setup_s = 0, step_s_median = 0;
  double final_kinetic_J = 0, final_strain_J = 0;
  integrators::Stats stats;
};

ScenarioRunSummary run_scenario(const scenario::Scenario& scenario, const std::filesystem::path& out, std::ostream& log);

}  // namespace roifem::simulation
