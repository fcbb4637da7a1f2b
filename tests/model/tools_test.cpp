// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/loads.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "model/energy.hpp"
#include "model/fem_model.hpp"
#include "model/prescribed_motion.hpp"
#include "test_models.hpp"

namespace roifem::model {
namespace {

using test::SpringMass;

/// Max |F - F_exact| over [0, 3T] stepping the eliminated system by the trapezoidal rule at dt.
double force_error(const SpringMass& sm, double dt, double* balance = nullptr) {
  const ToolElimination e = sm.eliminated();
  State s = State::at_rest(3);
  integrators::Trapezoid trapezoid(dt);
  trapezoid.reset(e.system, s);
  EnergyLedger ledger(e.system, s, &e.tools);
  double worst = 0;
  const long steps = std::lround(3 * sm.T / dt);
  for (long n = 1; n <= steps; ++n) {
    trapezoid.advance_to(static_cast<double>(n) * dt, s);
    ledger.record(s);
    const Vector F = e.tools.forces(s.u, s.t);
    worst = std::max(worst, std::abs(F[0] - sm.force(s.t)));
    EXPECT_EQ(F[1], 0.0);
    EXPECT_EQ(F[2], 0.0);
  }
  if (balance) *balance = std::abs(ledger.balance_residual()) / ledger.tool_work();
  EXPECT_LT(std::abs(ledger.external_work()), 1e-12 * ledger.tool_work());  // no load: all the work is the tool's
  return worst;
}

TEST(Tools, ASpringMassPulledByAToolFeelsTheAnalyticForceAtSecondOrder) {
  const SpringMass sm;
  double balance = 0;
  const double coarse = force_error(sm, 0.01), fine = force_error(sm, 0.005, &balance);
  const double peak = sm.k * sm.d / (sm.omega() * sm.T);  // the spring's force amplitude scale
  std::printf("spring-mass: max |F - F_exact| %.3e N (dt 0.01), %.3e N (dt 0.005): order %.2f; |balance| / W_tools %.1e\n",
              coarse, fine, std::log2(coarse / fine), balance);
  EXPECT_LT(fine, 2e-3 * peak);
  EXPECT_NEAR(std::log2(coarse / fine), 2.0, 0.15);
  EXPECT_LT(balance, 1e-10);
}

/// A 60 x 20 x 20 mm beam held at x = 0; a tool holds its far face (set x1).
struct PushedBeam {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  fem::Material material = fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8);
  SetTool tool{.name = "tip", .set = "x1", .path = {Vec3(0.2e-3, -0.1e-3, 1e-3), Ramp{0.2}}};
};

TEST(Tools, ACantileverTipHeldByAToolFeelsTheStiffnessCondensedOntoIt) {
  // Static: F = S (K_pp - K_pf K_ff^-1 K_fp) S^T g, from the model without the tool (dense).
  const PushedBeam b;
  const FemModel with = build_fem_model(b.mesh, b.material, {"x0"}, {}, {b.tool});
  const FemModel without = build_fem_model(b.mesh, b.material, {"x0"}, {});
  const Vec3 g = b.tool.path.displacement;
  std::vector<Index> p, f;
  const auto& tip = b.mesh.set("x1").nodes;
  for (Index i = 0; i < without.system.size(); ++i) {
    const Index node = without.dofs->full_dof(i) / 3;
    (std::binary_search(tip.begin(), tip.end(), node) ? p : f).push_back(i);
  }
  const DenseMatrix K = DenseMatrix(without.system.K);
  auto block = [&](const std::vector<Index>& r, const std::vector<Index>& c) {
    DenseMatrix B(r.size(), c.size());
    for (std::size_t i = 0; i < r.size(); ++i)
      for (std::size_t j = 0; j < c.size(); ++j) B(i, j) = K(r[i], c[j]);
    return B;
  };
  const DenseMatrix K_fp = block(f, p);
  const DenseMatrix schur = block(p, p) - K_fp.transpose() * block(f, f).llt().solve(K_fp);
  Vector G(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) G[i] = g[without.dofs->full_dof(p[i]) % 3];
  const Vector nodal = schur * G;
  Vec3 expected = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) expected[without.dofs->full_dof(p[i]) % 3] += nodal[i];

  const double t = 1.0;  // after the ramp
  const Vector u = DenseMatrix(with.system.K).llt().solve(with.system.load.at(t));
  const Vector F = with.tools.forces(u, t);
  std::printf("cantilever tip: F = (%.6e, %.6e, %.6e) N, condensed stiffness gives (%.6e, %.6e, %.6e)\n", F[0], F[1], F[2],
              expected[0], expected[1], expected[2]);
  EXPECT_LT((F - expected).norm(), 1e-10 * expected.norm());
  EXPECT_GT(expected[2], 0);  // pushing up takes an upward force
  // The field shows the tool's nodes where the tool has taken them.
  const Vector field = with.displacement(u, t);
  for (const int n : tip) EXPECT_EQ(Vec3(field.segment<3>(3 * n)), g);
}

TEST(Tools, TheTrapezoidalRuleKeepsTheEnergyBalanceWithToolsAndLoadsTo1e10) {
  const PushedBeam b;
  const FemModel m = build_fem_model(b.mesh, b.material, {"x0"}, {{"y1", Vec3(0, 0.02, 0), Ramp{0.1}}}, {b.tool});
  State s = State::at_rest(m.system.size());
  integrators::Trapezoid trapezoid(0.01);
  trapezoid.reset(m.system, s);
  EnergyLedger ledger(m.system, s, &m.tools);
  double worst = 0;
  for (int n = 1; n <= 300; ++n) {
    trapezoid.advance_to(0.01 * n, s);
    ledger.record(s);
    worst =
        std::max(worst, std::abs(ledger.balance_residual()) / (std::abs(ledger.tool_work()) + std::abs(ledger.external_work())));
  }
  std::printf(
      "beam with a tool and a load: max |E + D - W - W_tools - E0| / (|W| + |W_tools|) = %.2e (W %.3e J, W_tools %.3e J)\n",
      worst, ledger.external_work(), ledger.tool_work());
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(std::abs(ledger.external_work()), 1e-3 * std::abs(ledger.tool_work()));  // both did work
  EXPECT_GT(ledger.dissipated(), 0.0);
}

void expect_input_error(const std::function<void()>& build, const std::vector<std::string>& words) {
  try {
    build();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    for (const auto& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

TEST(Tools, BadToolsAndLoadsOnSupportsAreRefusedByName) {
  const PushedBeam b;
  auto with = [&](std::vector<SetTool> tools, std::vector<SetLoad> loads = {}) {
    return [&b, tools, loads] { build_fem_model(b.mesh, b.material, {"x0"}, loads, tools); };
  };
  SetTool nowhere{.name = "probe", .center = Vec3(1, 1, 1), .radius = 1e-3, .path = {}};
  expect_input_error(with({nowhere}), {"tool 'probe'", "holds no node", "within 1 mm"});
  SetTool on_base{.name = "clamp", .set = "x0", .path = {}};
  expect_input_error(with({on_base}), {"tool 'clamp'", "which [boundary] fixes"});
  SetTool other = b.tool;
  other.name = "second";
  expect_input_error(with({b.tool, other}), {"tool 'tip'", "tool 'second'", "both hold node"});
  expect_input_error(with({}, {{"x0", Vec3(1, 0, 0), Ramp{}}}), {"set 'x0'", "wholly on fixed nodes"});
  // A load that straddles the support: told how much of it is lost.
  const FemModel partly = build_fem_model(b.mesh, b.material, {"x0"}, {{"y0", Vec3(0, 0, 1), Ramp{}}});
  ASSERT_EQ(partly.warnings.size(), 1u);
  EXPECT_NE(partly.warnings[0].find("set 'y0' acts partly on fixed nodes"), std::string::npos) << partly.warnings[0];
  // Its lost share, independently: the load on nodes that x0 holds.
  const auto& fixed = b.mesh.set("x0").nodes;
  const Vector full = fem::set_force(b.mesh, "y0", Vec3(0, 0, 1));
  double lost = 0;
  for (const int n : fixed) lost += full.segment<3>(3 * n).squaredNorm();
  EXPECT_NE(partly.warnings[0].find(format("%.3g N", std::sqrt(lost))), std::string::npos) << partly.warnings[0];
}

TEST(Tools, ToolsThatHoldEveryFreeNodeLeaveNothingToIntegrate) {
  // A 2 x 2 x 2-node cube held at x = 0 with a tool on x = 1: no unknown is left. This reached
  // CHOLMOD, SUNDIALS or GSL as an empty system ("CHOLMOD analysis failed (status -4)").
  const mesh::TetMesh cube = mesh::structured_box_mesh(1, 1, 1, 0.02, 0.02, 0.02);
  const fem::Material material = fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8);
  try {
    build_fem_model(cube, material, {"x0"}, {}, {SetTool{.name = "lid", .set = "x1", .path = {}}});
    FAIL() << "an empty model was built";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("the tools ('lid') hold every free node (4): nothing is left to integrate"),
              std::string::npos)
        << e.what();
  }
}

TEST(Tools, AToolBelowTheMeshsSizeIsWarnedOf) {
  // On the beam (10 mm elements) a ball of 1 mm around a corner of the far face holds one node.
  const PushedBeam b;
  SetTool probe{.name = "probe", .center = Vec3(0.06, 0.02, 0.02), .radius = 1e-3, .path = {Vec3(0, 0, 1e-3), Ramp{0.2}}};
  const FemModel one = build_fem_model(b.mesh, b.material, {"x0"}, {}, {probe});
  ASSERT_EQ(one.warnings.size(), 1u);
  EXPECT_NE(one.warnings[0].find("tool 'probe' (boundary nodes within 1 mm of (60, 20, 20) mm) holds 1 node, and the elements "
                                 "there have"),
            std::string::npos)
      << one.warnings[0];
  EXPECT_NE(one.warnings[0].find("give it a footprint of 3 nodes or more"), std::string::npos) << one.warnings[0];
  // The whole far face (9 nodes) is a footprint: no word.
  EXPECT_TRUE(build_fem_model(b.mesh, b.material, {"x0"}, {}, {b.tool}).warnings.empty());
}

}  // namespace
}  // namespace roifem::model
