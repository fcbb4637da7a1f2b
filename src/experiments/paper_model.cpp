// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/paper_model.hpp"

#include <algorithm>

#include "fem/static_solve.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::experiments {

namespace {

/// Mean x-displacement of a set's nodes (m).
double mean_x(const mesh::TetMesh& mesh, const Vector& u_full, const std::string& set) {
  const auto& nodes = mesh.set(set).nodes;
  double sum = 0;
  for (int n : nodes) sum += u_full[3 * n];
  return sum / static_cast<double>(nodes.size());
}

/// The forces' model: unit forces (1 N per wall, opposite directions), scaled to the opening by
/// the linear model (K, the tangent at rest whatever the law).
void add_opening_forces(const fem::Material& material, const std::string& fixed_set, double opening_mm, PaperModel& m) {
  m.full = model::build_fem_model(
      m.mesh, material, {fixed_set},
      {{"opening_left", Vec3(-1, 0, 0), model::Ramp{0}}, {"opening_right", Vec3(1, 0, 0), model::Ramp{0}}});
  const fem::DofMap& dofs = *m.full.dofs;
  solvers::Cholesky K;
  fem::factorize_stiffness(K, m.full.system.K, dofs);
  const Vector u = dofs.expand(K.solve(m.full.system.load.at(1.0)));
  const double opening_per_newton = mean_x(m.mesh, u, "opening_right") - mean_x(m.mesh, u, "opening_left");
  m.force_N = opening_mm * mm / opening_per_newton;
  m.full.system.load = m.full.system.load.mapped(dofs.num_free(), [&](const Vector& p) { return Vector(m.force_N * p); });
}

/// The spatulas' model: each wall's nodes held by a rigid tool that moves it opening_mm / 2
/// outwards; the force each spatula holds at rest in the linear model.
void add_spatulas(const fem::Material& material, const std::string& fixed_set, double opening_mm, PaperModel& m) {
  const double half = opening_mm * mm / 2;
  auto spatula = [&](const char* name, const char* set, double direction) {
    return model::SetTool{.name = name,
                          .set = set,
                          .center = Vec3::Zero(),
                          .radius = 0,
                          .path = {.displacement = Vec3(direction * half, 0, 0), .ramp = model::Ramp{0}}};
  };
  m.full = model::build_fem_model(m.mesh, material, {fixed_set}, {},
                                  {spatula("left", "opening_left", -1), spatula("right", "opening_right", 1)});
  solvers::Cholesky K;
  fem::factorize_stiffness(K, m.full.system.K, *m.full.dofs);
  const Vector u = K.solve(m.full.system.load.at(1.0));
  // The linear tools' forces: coupling u + self g (the law's correction vanishes at rest only).
  const Vector forces = m.full.tools.with_law(nullptr).forces(u, 1.0);
  m.force_N = std::max(forces.segment<3>(0).norm(), forces.segment<3>(3).norm());
}

}  // namespace

std::unique_ptr<PaperModel> build_paper_model(const mesh::TetMesh& mesh, const fem::Material& material,
                                              const std::string& fixed_set, PaperDrive drive, double opening_mm) {
  auto m = std::make_unique<PaperModel>();
  m->mesh = mesh;
  if (drive == PaperDrive::forces)
    add_opening_forces(material, fixed_set, opening_mm, *m);
  else
    add_spatulas(material, fixed_set, opening_mm, *m);
  return m;
}

std::vector<int> select_setup_nodes(const PaperModel& m, const roi::RoiSpec& spec) {
  const fem::DofMap& choose_among = m.full.dofs_with_tools ? *m.full.dofs_with_tools : *m.full.dofs;
  std::vector<int> nodes = roi::select_roi_nodes(m.mesh, choose_among, spec);
  const std::vector<int> free = roi::free_nodes(m.mesh, *m.full.dofs);
  std::erase_if(nodes, [&](int n) { return !std::binary_search(free.begin(), free.end(), n); });
  return nodes;
}

std::pair<double, double> force_error_mN(const Vector& forces, const Vector& reference) {
  double error = 0, largest = 0;
  for (Index a = 0; 3 * a < forces.size(); ++a) {
    error = std::max(error, (forces.segment<3>(3 * a) - reference.segment<3>(3 * a)).norm() / 1e-3);
    largest = std::max(largest, reference.segment<3>(3 * a).norm() / 1e-3);
  }
  return {error, largest};
}

}  // namespace roifem::experiments
