// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The copies a split plan reserves (split_plan.hpp), held in a model from the start: below both
/// the model's builder and the splits that take them in (simulation/cuts/scenario_splits.hpp).
#include <vector>

#include "cutting/split_plan.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/fem_model.hpp"

namespace roifem::cutting {

/// Per copy of `plan` (node plan.num_nodes + k of `mesh`), its stand-in mass while it is held:
/// its original's lumped mass in the uncut mesh (kg).
std::vector<double> copy_stand_in_mass(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const SplitPlan& plan);

/// Holds the copies of `full` (built on the mesh with_copies(plan)): their stand-in mass in M
/// (and C = alpha M), no stiffness, no load.
void hold_copies(model::FemModel& full, const SplitPlan& plan);

}  // namespace roifem::cutting
