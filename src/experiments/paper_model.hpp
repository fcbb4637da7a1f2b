// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The paper's full model (Hansen & Larsen 1998, Section 5) under either drive, shared by
/// `roifem paper` (paper_experiment.hpp) and its large-deformation form (paper_large_deformation.hpp):
/// the shipped brain, base fixed, the opening widened by two forces (scaled so that the linear
/// model's static opening widens by opening_mm) or by two spatulas that move its walls opening_mm
/// apart. The scale is the linear model's whatever the law, so that a neo-Hookean model runs under
/// the same loads.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "experiments/paper_results.hpp"
#include "fem/material.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/fem_model.hpp"
#include "roi/roi.hpp"

namespace roifem::experiments {

/// The full model refers to the mesh: held by unique_ptr.
struct PaperModel {
  mesh::TetMesh mesh;
  model::FemModel full;
  double force_N = 0;  ///< per wall: applied (forces), or held at rest by the linear model (spatulas)
};

/// The paper's model of `mesh` (read and checked) with `material` (a preset with its law), driven
/// as asked, its base `fixed_set` held.
std::unique_ptr<PaperModel> build_paper_model(const mesh::TetMesh& mesh, const fem::Material& material,
                                              const std::string& fixed_set, PaperDrive drive, double opening_mm);

/// The setup's ROI: the same nodes whichever the drive, chosen among the nodes the base leaves free
/// (the walls' included); those a spatula holds then leave the unknowns and move with it.
std::vector<int> select_setup_nodes(const PaperModel& m, const roi::RoiSpec& spec);

/// The largest of the tools' forces' differences and the largest reference force (mN), at one step.
std::pair<double, double> force_error_mN(const Vector& forces, const Vector& reference);

}  // namespace roifem::experiments
