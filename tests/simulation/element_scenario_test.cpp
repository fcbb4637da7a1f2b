// SPDX-License-Identifier: GPL-3.0-or-later
// A scenario's `element`: the nodal-pressure and 10-node tetrahedra reach the model, static
// condensation stays exact at rest with their wider stiffness patterns, the nearly incompressible
// paper brain is less stiff than with linear tetrahedra (which lock), the 10-node model's static
// answer is CalculiX's C3D10 on the same mesh, and the trapezoidal rule conserves either's energy.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cstdio>
#include <sstream>

#include "experiments/calculix_static.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "fem/nodal_pressure.hpp"
#include "integrators/trapezoid.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

scenario::Scenario paper_setup1(const std::string& element) {
  const std::string text = "mesh = \"" + std::string(ROIFEM_MESH_DIR) + "/brain-800.msh\"\nelement = \"" + element + "\"\n" +
                           R"([material]
preset = "paper"
[[load]]
set = "opening_left"
force_N = [-0.016, 0, 0]
ramp_s = 0.5
[[load]]
set = "opening_right"
force_N = [0.016, 0, 0]
ramp_s = 0.5
[roi]
kind = "nearest"
target_mm = [0, 0, 40]
nodes = 306
)";
  return scenario::parse_scenario(text, "setup1.toml", ROIFEM_MESH_DIR);
}

/// The static opening (m): the mean x displacement of the right wall minus the left's.
double opening(const ScenarioModel& m, const Vector& u_free) {
  const Vector u = m.full.dofs->expand(u_free);
  double right = 0, left = 0;
  for (int n : m.mesh.set("opening_right").nodes) right += u[3 * n];
  for (int n : m.mesh.set("opening_left").nodes) left += u[3 * n];
  return right / static_cast<double>(m.mesh.set("opening_right").nodes.size()) -
         left / static_cast<double>(m.mesh.set("opening_left").nodes.size());
}

/// The static answer of a system under its loads at t = 1 s (after every ramp).
Vector static_solution(const model::SecondOrderSystem& system) {
  return Eigen::SimplicialLDLT<SparseMatrix>(system.K).solve(system.load.at(1.0));
}

/// The largest difference between the condensed model's static answer and the full one's
/// (u_full) over the ROI's dofs.
double condensation_gap(const ScenarioModel& m, const Vector& u_full) {
  const Vector u_roi = static_solution(m.system());
  const auto& d = m.condensation->partition().d;
  double worst = 0;
  for (std::size_t i = 0; i < d.size(); ++i) worst = std::max(worst, std::abs(u_roi[static_cast<Index>(i)] - u_full[d[i]]));
  return worst;
}

TEST(ElementScenario, TheNodalPressureTetrahedronReachesTheModelAndCondensesExactlyAtRest) {
  const auto tet4 = build_scenario_model(paper_setup1("tet4"));
  const auto nodal = build_scenario_model(paper_setup1("nodal-pressure"));
  const SparseMatrix direct = fem::nodal_pressure_stiffness(nodal->mesh, *nodal->full.dofs, nodal->full.material, 0.0);
  EXPECT_EQ((nodal->full.system.K - direct).norm(), 0.0);
  std::printf("paper brain: K has %lld non-zeros (tet4), %lld (nodal pressure)\n",
              static_cast<long long>(tet4->full.system.K.nonZeros()), static_cast<long long>(nodal->full.system.K.nonZeros()));
  EXPECT_GT(nodal->full.system.K.nonZeros(), 2 * tet4->full.system.K.nonZeros());

  // At rest, static condensation is exact: the condensed model's static answer is the full one's
  // over the ROI.
  const Vector u_full = static_solution(nodal->full.system);
  EXPECT_LT(condensation_gap(*nodal, u_full), 1e-9 * u_full.cwiseAbs().maxCoeff());

  // The paper's material (nu = 0.4985) locks linear tetrahedra: the same forces open the slit
  // wider with nodal pressures.
  const Vector u_tet4 = static_solution(tet4->full.system);
  const double o_tet4 = opening(*tet4, u_tet4), o_nodal = opening(*nodal, u_full);
  std::printf("paper brain, 16 mN per wall: static opening %.3f mm (tet4), %.3f mm (nodal pressure)\n", o_tet4 / mm,
              o_nodal / mm);
  EXPECT_GT(o_nodal, 1.2 * o_tet4);
}

/// The static opening (m) as the loads do work on it: the area-weighted means of the walls.
double mean_opening(const mesh::TetMesh& mesh, const Vector& u) {
  return fem::set_mean_displacement(mesh, "opening_right", u).x() - fem::set_mean_displacement(mesh, "opening_left", u).x();
}

TEST(ElementScenario, TheTenNodeTetrahedronCondensesExactlyAndIsCalculixsC3d10) {
  const auto tet10 = build_scenario_model(paper_setup1("tet10"));
  const mesh::TetMesh& q = tet10->mesh;
  ASSERT_TRUE(q.is_quadratic());
  EXPECT_EQ((tet10->full.system.K - fem::StiffnessAssembler(q, *tet10->full.dofs).stiffness(tet10->full.material)).norm(), 0.0);
  // HRZ: the model's mass is the brain's.
  const Vector m = fem::lumped_node_mass(q, tet10->full.material.rho);
  EXPECT_NEAR(m.sum(), tet10->full.material.rho * mesh::total_volume(q), 1e-12 * m.sum());

  // At rest, static condensation is exact.
  const Vector u_full = static_solution(tet10->full.system);
  EXPECT_LT(condensation_gap(*tet10, u_full), 1e-9 * u_full.cwiseAbs().maxCoeff());

  // The same mesh, supports and loads solved by CalculiX with C3D10 elements.
  const double opening_roifem = mean_opening(q, tet10->full.dofs->expand(u_full));
  std::printf("paper brain, 16 mN per wall: static opening %.4f mm (tet10, %lld dofs)\n", opening_roifem / mm,
              static_cast<long long>(tet10->full.system.size()));
  if (!experiments::calculix_available())
    GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  const test::TempDir dir;
  experiments::CalculixProblem problem{.mesh = &q, .material = tet10->full.material, .fixed_nodes = q.set("base").nodes};
  problem.forces = fem::set_force(q, "opening_left", Vec3(-0.016, 0, 0)) + fem::set_force(q, "opening_right", Vec3(0.016, 0, 0));
  std::ostringstream log;
  const Vector u_ccx = experiments::solve_with_calculix(problem, {1.0}, false, dir.path(), log).front().u;
  const double opening_ccx = mean_opening(q, u_ccx);
  std::printf("  CalculiX C3D10 on the same nodes: %.4f mm\n", opening_ccx / mm);
  EXPECT_NEAR(opening_roifem, opening_ccx, 1e-5 * opening_ccx);
  EXPECT_LT((tet10->full.dofs->expand(u_full) - u_ccx).cwiseAbs().maxCoeff(), 1e-5 * u_ccx.cwiseAbs().maxCoeff());
}

class UndampedModel : public ::testing::TestWithParam<const char*> {};

TEST_P(UndampedModel, ConservesTheTrapezoidalRulesEnergy) {
  // Without damping and load, the trapezoidal rule conserves v^T M v / 2 + u^T K u / 2 exactly
  // for any constant symmetric K, started with a velocity field.
  const auto nodal = build_scenario_model(paper_setup1(GetParam()));
  model::SecondOrderSystem system = nodal->full.system;
  system.C = 0 * system.C;
  system.damping = model::Damping::mass_proportional(0);
  system.load = model::LoadHistory(system.size());
  model::State s = model::State::at_rest(system.size());
  s.v = Vector::LinSpaced(system.size(), -1e-3, 1e-3);
  auto energy = [&] { return 0.5 * s.v.dot(system.M * s.v) + 0.5 * s.u.dot(system.K * s.u); };
  const double initial = energy();
  integrators::Trapezoid trapezoid(0.05);
  trapezoid.reset(system, s);
  double worst = 0;
  for (int k = 0; k < 100; ++k) {
    trapezoid.step(s);
    worst = std::max(worst, std::abs(energy() - initial));
  }
  EXPECT_GT(s.u.norm(), 0.0);
  EXPECT_LT(worst, 1e-10 * initial);
}

INSTANTIATE_TEST_SUITE_P(ElementScenario, UndampedModel, ::testing::Values("nodal-pressure", "tet10"),
                         [](const auto& instance) { return std::string(instance.param) == "tet10" ? "Tet10" : "NodalPressure"; });

}  // namespace
}  // namespace roifem::simulation
