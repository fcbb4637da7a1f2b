// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The linear model's own error: roifem's small-strain answer against the geometrically nonlinear
/// one CalculiX computes (experiments/calculix_static.hpp) on the same mesh, material, supports
/// and set forces, at growing fractions of the load. Both use the linear tetrahedron (C3D4), so
/// the difference is the kinematics alone. Before it is trusted, CalculiX's small-strain answer
/// on the same deck is checked against roifem's (linear_check).
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "fem/material.hpp"
#include "model/fem_model.hpp"

namespace roifem::experiments {

struct ModelErrorRow {
  double fraction = 0;
  double opening_linear_mm = 0, opening_nonlinear_mm = 0;  ///< area-weighted, as the convergence study's
  double max_displacement_nonlinear_mm = 0;                ///< the largest nodal |u| of the nonlinear answer
  double max_difference_mm = 0;                            ///< the largest nodal |u_linear - u_nonlinear|
  double relative() const { return max_difference_mm / max_displacement_nonlinear_mm; }
  double opening_relative() const { return std::abs(opening_linear_mm - opening_nonlinear_mm) / std::abs(opening_nonlinear_mm); }
};

struct ModelErrorStudy {
  std::vector<ModelErrorRow> rows;  ///< the fractions CalculiX reached
  double linear_check = 0;          ///< max |u_ccx,linear - u_roifem| / max |u_roifem| at the full load
  /// The opening (mm, linear) up to which the largest nodal difference stays within 10% of the largest
  /// displacement (interpolated between fractions); none when it does at every fraction reached.
  std::optional<double> within_10_percent_up_to_mm;
  Vector u_linear, u_nonlinear;  ///< m, 3N, at fraction 1 (when reached)
  bool full_load_reached = false;
};

/// Solves the static problem under `loads` (set forces, taken at their full value) with
/// roifem (tet4) and with CalculiX, small-strain and NLGEOM, in `work_dir`. The mesh must have
/// opening_left and opening_right. Throws SolverError when CalculiX is missing or fails.
ModelErrorStudy measure_model_error(const mesh::TetMesh& mesh, const fem::Material& material,
                                    const std::vector<std::string>& fixed_sets, const std::vector<model::SetLoad>& loads,
                                    const std::vector<double>& fractions, const std::filesystem::path& work_dir,
                                    std::ostream& log);

/// Prints the linear-versus-nonlinear table.
void print_model_error(const ModelErrorStudy& study, std::ostream& log);

}  // namespace roifem::experiments
