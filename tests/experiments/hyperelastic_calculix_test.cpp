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

}  // namespace
}  // namespace roifem::experiments
