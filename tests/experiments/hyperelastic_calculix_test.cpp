// SPDX-License-Identifier: GPL-3.0-or-later
// The static neo-Hookean answer on the paper's brain (806 nodes, fixed base, 16.01 mN pulling each
// wall of the opening apart, the paper's material) against CalculiX's (*HYPERELASTIC, NEO HOOKE,
// NLGEOM, the same nodes and elements): C3D4 at 10%, 50% and 100% of the load; C3D10 on the brain
// with midside nodes at 10%, 20% and 35%. An independent code with its own element, law and Newton
// solver. The 10-node brain does not lock, deforms several times more, and reaches a limit point
// at 40% of the load (the tangent turns indefinite: the soft paper material, mu = 12 Pa, buckles):
// roifem's static path ends at 0.4016 of the load and CalculiX's at 0.4020.
// CalculiX's Newton tolerance is 1e-9 of its increment's mean force: its default, 5e-3, leaves an
// error near 1e-3, and 1e-7 still 4e-5 on this soft, nearly incompressible material.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "experiments/calculix_static.hpp"
#include "fem/assembly.hpp"
#include "fem/hyperelastic_static.hpp"
#include "fem/loads.hpp"
#include "fem/static_solve.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

double max_nodal_norm(const Vector& u) {
  double m = 0;
  for (Index n = 0; n < u.size() / 3; ++n) m = std::max(m, u.segment<3>(3 * n).norm());
  return m;
}

void compare_with_calculix(const mesh::TetMesh& mesh, const char* name, const std::vector<double>& fractions) {
  fem::Material material = fem::material_preset("paper");
  material.model = fem::MaterialModel::neo_hookean;
  const double force = 0.01601;  // N per wall: scenarios/paper-full.toml
  const Vector forces =
      fem::set_force(mesh, "opening_left", Vec3(-force, 0, 0)) + fem::set_force(mesh, "opening_right", Vec3(force, 0, 0));
  CalculixProblem problem{.mesh = &mesh,
                          .material = material,
                          .fixed_nodes = mesh.set("base").nodes,
                          .forces = forces,
                          .newton_tolerance = 1e-9,
                          .step_per_fraction = true};
  std::ostringstream log;
  // Each run its own directory: two test runs at once (Release and sanitized) shared
  // /tmp/roifem_neo_hooke_C3D10 and overwrote each other's CalculiX files.
  const test::TempDir scratch;
  const auto dir = scratch / (std::string("neo_hooke_") + name);
  const auto ccx = solve_with_calculix(problem, fractions, true, dir, log);
  ASSERT_EQ(ccx.size(), fractions.size()) << log.str();

  fem::Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "base");
  const fem::DofMap dofs(constraints);
  const fem::MaterialMap materials(material);
  const fem::HyperelasticAssembler assembler(mesh, dofs, materials);
  const auto ours = fem::solve_hyperelastic_static(assembler, dofs, dofs.restrict_to_free(forces), fractions);
  const Vector u_linear = dofs.expand(
      fem::solve_static(fem::StiffnessAssembler(mesh, dofs).stiffness(materials), dofs.restrict_to_free(forces), dofs));
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const Vector u = dofs.expand(ours[k].u_free);
    const double scale = max_nodal_norm(ccx[k].u);
    const double difference = max_nodal_norm(u - ccx[k].u) / scale;
    const double linear = max_nodal_norm(fractions[k] * u_linear - ccx[k].u) / scale;
    int iterations = 0;
    for (const auto& r : ours[k].newton) iterations += r.iterations();
    std::printf(
        "%s, %3.0f%% load: max |u| %.4f mm; max |u - u_ccx| / max |u_ccx| = %.2e (the linear answer's: %.2e); %zu "
        "increments, %d Newton iterations\n",
        name, 100 * fractions[k], scale / mm, difference, linear, ours[k].newton.size(), iterations);
    EXPECT_LT(difference, 1e-5) << name << " at " << fractions[k];
    EXPECT_GT(linear, 100 * difference) << "the comparison tells the two laws apart";
  }
}

class NeoHookeanAgainstCalculix : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  }
};

TEST_F(NeoHookeanAgainstCalculix, PaperBrainWithC3D4) {
  compare_with_calculix(mesh::read_mesh(ROIFEM_MESH_DIR "/brain-800.msh"), "C3D4", {0.1, 0.5, 1.0});
}

TEST_F(NeoHookeanAgainstCalculix, PaperBrainWithC3D10) {
  compare_with_calculix(mesh::with_midside_nodes(mesh::read_mesh(ROIFEM_MESH_DIR "/brain-800.msh")), "C3D10", {0.1, 0.2, 0.35});
}

/// A 10 mm cube of brain tissue (mu = 1 kPa, nu = 0.45) as one Ogden term with alpha = -20, its
/// base held, pressed down or pulled up by `force` N on its top face, against CalculiX's
/// *HYPERELASTIC, OGDEN, N=1 on the same nodes and elements: max |u - u_ccx| / max |u_ccx| at each
/// fraction, and the largest displacement at full load (m).
std::pair<double, double> ogden_cube_against_calculix(bool quadratic, double force, const char* name) {
  const mesh::TetMesh linear = mesh::unstructured_box_mesh(0.01, 0.01, 0.01, 0.0025);
  const mesh::TetMesh mesh = quadratic ? mesh::with_midside_nodes(linear) : linear;
  fem::Material material = fem::material_preset("brain");
  material.model = fem::MaterialModel::ogden;
  material.ogden = {{material.mu, -20}};
  material.validate();
  const Vector forces = fem::set_force(mesh, "z1", Vec3(0, 0, force));
  const std::vector<double> fractions{0.1, 0.5, 1.0};
  CalculixProblem problem{.mesh = &mesh,
                          .material = material,
                          .fixed_nodes = mesh.set("z0").nodes,
                          .forces = forces,
                          .newton_tolerance = 1e-9,
                          .step_per_fraction = true};
  std::ostringstream log;
  const test::TempDir scratch;
  const auto ccx = solve_with_calculix(problem, fractions, true, scratch / (std::string("ogden_") + name), log);
  EXPECT_EQ(ccx.size(), fractions.size()) << log.str();
  if (ccx.size() != fractions.size()) return {1, 0};
  fem::Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "z0");
  const fem::DofMap dofs(constraints);
  const fem::MaterialMap materials(material);
  const fem::HyperelasticAssembler assembler(mesh, dofs, materials);
  const auto ours = fem::solve_hyperelastic_static(assembler, dofs, dofs.restrict_to_free(forces), fractions);
  double worst = 0;
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const Vector u = dofs.expand(ours[k].u_free);
    const double scale = max_nodal_norm(ccx[k].u);
    const double difference = max_nodal_norm(u - ccx[k].u) / scale;
    std::printf("Ogden (alpha = -20) cube, %s, %3.0f%% load: max |u| %.4f mm; max |u - u_ccx| / max |u_ccx| = %.2e\n", name,
                100 * fractions[k], scale / mm, difference);
    worst = std::max(worst, difference);
  }
  return {worst, max_nodal_norm(ccx.back().u)};
}

TEST_F(NeoHookeanAgainstCalculix, OgdenCubeInCompressionAndTensionWithC3D4AndC3D10) {
  // 80 mN on 1 cm^2: 800 Pa, about the cortex's stress at 10% compression (Budday et al. 2017).
  const double force = 0.08;
  const auto [c4, pressed4] = ogden_cube_against_calculix(false, -force, "C3D4 pressed");
  const auto [t4, pulled4] = ogden_cube_against_calculix(false, force, "C3D4 pulled");
  const auto [c10, pressed10] = ogden_cube_against_calculix(true, -force, "C3D10 pressed");
  EXPECT_LT(c4, 1e-5);
  EXPECT_LT(t4, 1e-5);
  EXPECT_LT(c10, 1e-5);
  // alpha = -20: the same force moves the top much less pressed than pulled.
  EXPECT_LT(pressed4, 0.5 * pulled4);
}

}  // namespace
}  // namespace roifem::experiments
