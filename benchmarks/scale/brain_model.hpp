// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The benchmarks' brain model, built the way `roifem paper` builds its models: paper material,
/// base fixed, the opening's walls pulled apart over 0.5 s (the force of scenarios/paper-setup1.toml);
/// and its condensation onto the ROI of the nodes nearest the surgical target (0, 0, 40) mm.
#include <filesystem>
#include <memory>

#include "condensation/reduced_model.hpp"
#include "fem/material_model.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/fem_model.hpp"

namespace roifem::bench {

struct Brain {
  mesh::TetMesh mesh;
  model::FemModel model;
  double read_s = 0, assembly_s = 0;  ///< mesh read and checked; dof map, K, M, C and loads
};

/// Reads and checks the mesh, assembles the model: the paper's material (its law `model`: linear,
/// or neo-Hookean with the same lambda and mu) and its wall forces times `load_scale`.
std::unique_ptr<Brain> build_brain(const std::filesystem::path& mesh_file, fem::MaterialModel model = fem::MaterialModel::linear,
                                   double load_scale = 1);

/// The `count` free nodes nearest the target.
roi::RoiSpec nearest_target(Index count);

struct Condensed {
  std::unique_ptr<condensation::ReducedModel> condensation;
  long interface_dofs = 0;
};

/// Static condensation onto the `roi_nodes` nodes nearest the target.
Condensed condense(const Brain& brain, Index roi_nodes);

/// The process's peak resident memory (MB).
double peak_rss_mb();

}  // namespace roifem::bench
