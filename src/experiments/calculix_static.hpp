// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A geometrically nonlinear reference from an existing solver: CalculiX (Debian's calculix-ccx)
/// solves the same mesh (C3D4, the same linear tetrahedra), material (*ELASTIC: with NLGEOM the
/// St. Venant-Kirchhoff law, linear in Green-Lagrange strain; a neo-Hookean material as
/// *HYPERELASTIC, NEO HOOKE with C10 = mu/2, D1 = 2/kappa), supports and nodal forces, with
/// *STATIC and NLGEOM: the deck is written here, ccx run in a work directory, and its printed
/// displacements read back at each requested load fraction. Without NLGEOM the same deck is the
/// small-strain problem roifem solves, a check of the deck itself.
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "common/types.hpp"
#include "fem/material.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::experiments {

struct CalculixProblem {
  /// C3D4 elements, or C3D10 on a quadratic mesh (mesh/quadratic_mesh.hpp: straight-sided, in
  /// CalculiX's node order).
  const mesh::TetMesh* mesh = nullptr;
  fem::Material material;
  std::vector<int> fixed_nodes;                      ///< held in all three components
  std::vector<std::pair<int, int>> held_components;  ///< (node, component 0..2) held, as on a symmetry plane
  Vector forces;                                     ///< N, 3N: the full load (fraction 1)
  /// CalculiX's Newton tolerances R_n and C_n (*CONTROLS, PARAMETERS=FIELD: the largest residual
  /// force against the mean force, and the largest correction against the largest increment);
  /// 0 keeps its defaults (0.005 and 0.01), which leave an error near 1e-3.
  double newton_tolerance = 0;
  /// Each fraction the end of a *STEP of its own (the load ramped from the previous one), so that
  /// CalculiX solves there. Otherwise one step prints at *TIME POINTS, which it interpolates between
  /// its increments: up to 5e-4 off on the 10-node brain, where the step's end agrees to 2e-7.
  bool step_per_fraction = false;
};

struct CalculixSolution {
  double fraction = 0;
  Vector u;  ///< m, 3 per node
};

/// Whether `ccx` is on the PATH.
bool calculix_available();

/// Solves the problem at each load fraction (ascending, positive), NLGEOM or not, in `work_dir`
/// (deck, log and results stay there). Returns the fractions reached: when CalculiX stops early
/// (the increment shrinks below its minimum), the solutions before it, and a line in `log`.
/// Throws SolverError when ccx is missing, fails to start, or returns no solution at all.
std::vector<CalculixSolution> solve_with_calculix(const CalculixProblem& problem, const std::vector<double>& fractions,
                                                  bool nlgeom, const std::filesystem::path& work_dir, std::ostream& log);

}  // namespace roifem::experiments
