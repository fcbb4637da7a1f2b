// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The parts of a CalculiX deck that its static and dynamic problems share (experiments/
/// calculix_static.hpp, experiments/calculix_dynamic.hpp): the model (nodes, elements, supports,
/// material, section) in mm, N, MPa and t/mm^3, the nodal loads, the Newton controls, running ccx
/// and reading the displacements it prints.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "experiments/calculix_static.hpp"

namespace roifem::experiments::calculix {

/// Nodes, elements, supports and the material of `p`, then `material_lines` (keyword lines of the
/// same *MATERIAL: *DENSITY, *DAMPING) and the section. Node and element numbers are 1-based;
/// roifem's positive orientation is C3D4's. Numbers keep 13 digits: ccx reads a field of at most
/// 20 characters.
void write_model(const CalculixProblem& p, std::ostream& out, const std::string& material_lines = "");

/// *CLOAD of the nodal forces at `scale` of the full load, on `amplitude` where one is named.
void write_loads(const CalculixProblem& p, double scale, std::ostream& out, const std::string& amplitude = "");

/// *CONTROLS, PARAMETERS=FIELD: CalculiX's Newton tolerances R_n and C_n (the residual against the
/// mean force, the correction against the increment), q0 and qu left to CalculiX, R_P at its
/// default 0.02, and epsilon, below which it takes the residual for zero and converges whatever the
/// correction (default 1e-5: the 10-node brain's increments then stop after two iterations with a
/// 1-3% correction, 3e-5 off), then C_epsilon and C_f at their defaults.
std::string field_controls(double tolerance);

/// Runs `ccx -i job` in `work_dir` (its output in job.log there); returns its exit status. Throws
/// SolverError when ccx is not on the PATH.
int run_ccx(const std::filesystem::path& work_dir, const std::string& job);

/// The displacement blocks of a .dat file (*NODE PRINT ... U), in the order printed, with their
/// times (metres, 3 per node).
std::vector<std::pair<double, Vector>> read_displacements(const std::filesystem::path& file, Index nodes);

}  // namespace roifem::experiments::calculix
