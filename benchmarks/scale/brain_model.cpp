// SPDX-License-Identifier: GPL-3.0-or-later
#include "scale/brain_model.hpp"

#include <sys/resource.h>

#include "common/timer.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::bench {

namespace {
constexpr double wall_force_N = 0.01601;  // as scenarios/paper-setup1.toml
}  // namespace

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

std::unique_ptr<Brain> build_brain(const std::filesystem::path& mesh_file, fem::MaterialModel model, double load_scale) {
  auto brain = std::make_unique<Brain>();
  Stopwatch clock;
  brain->mesh = mesh::read_mesh(mesh_file);
  mesh::check_mesh(brain->mesh);
  brain->read_s = clock.seconds();
  clock.restart();
  fem::Material material = fem::material_preset("paper");
  material.model = model;
  const double force = wall_force_N * load_scale;
  brain->model = model::build_fem_model(
      brain->mesh, material, {"base"},
      {{"opening_left", Vec3(-force, 0, 0), model::Ramp{0.5}, {}}, {"opening_right", Vec3(force, 0, 0), model::Ramp{0.5}, {}}});
  brain->assembly_s = clock.seconds();
  return brain;
}

roi::RoiSpec nearest_target(Index count) {
  return {.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 40 * mm), .radius = 0, .count = count, .set = {}};
}

Condensed condense(const Brain& brain, Index roi_nodes) {
  const auto& dofs = *brain.model.dofs;
  const auto partition =
      roi::partition_dofs(brain.model.system.K, dofs, roi::select_roi_nodes(brain.mesh, dofs, nearest_target(roi_nodes)));
  Condensed c;
  c.interface_dofs = static_cast<long>(partition.interface.size());
  c.condensation = std::make_unique<condensation::ReducedModel>(brain.model.system, partition, dofs);
  return c;
}

}  // namespace roifem::bench
