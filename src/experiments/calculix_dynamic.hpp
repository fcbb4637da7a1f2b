// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// CalculiX's own nonlinear dynamics as an independent check of roifem's (section 2 of the large-
/// deformation work): the problem of experiments/calculix_static.hpp with the load ramped linearly
/// over `ramp_s` and then held, integrated by *DYNAMIC, DIRECT (fixed increments dt), ALPHA = 0
/// (Hilber-Hughes-Taylor at alpha = 0: Newmark's average acceleration, roifem's trapezoidal rule),
/// NLGEOM, with Rayleigh damping *DAMPING, ALPHA = the material's alpha (C = alpha M), from rest.
///
/// The mass matrix: CalculiX's implicit dynamics assembles the consistent mass of C3D4 and C3D10
/// from *DENSITY (it lumps only in its explicit scheme). roifem's is lumped (rho V / 4 per node for
/// tet4). `lumped` gives CalculiX the same lumped mass as MASS elements at the nodes (the solid's
/// density zero), so that the two solve the same ODE; `consistent` gives it the density and lets it
/// assemble its own, so that the difference is the mass discretization's.
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "experiments/calculix_static.hpp"

namespace roifem::experiments {

enum class CalculixMass { lumped, consistent };

struct CalculixDynamicProblem {
  CalculixProblem model;  ///< the material's rho and alpha are used; newton_tolerance as there
  double ramp_s = 0;      ///< the load rises linearly from 0 at t = 0 to full at ramp_s, then stays
  double dt = 0;
  long steps = 0;
  CalculixMass mass = CalculixMass::lumped;
  Vector lumped_mass;  ///< kg, one per node: the nodal masses for CalculixMass::lumped
};

/// The displacements at t = dt, 2 dt, ..., steps dt (metres, 3 per node), in `work_dir`. Throws
/// SolverError when ccx is missing or returns fewer steps than asked (naming its log).
std::vector<Vector> solve_dynamics_with_calculix(const CalculixDynamicProblem& problem, const std::filesystem::path& work_dir);

}  // namespace roifem::experiments
