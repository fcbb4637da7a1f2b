// SPDX-License-Identifier: GPL-3.0-or-later
// Tools on a neo-Hookean model (model/hyperelastic_force.hpp's motion): a tool that holds the free
// end of a cantilever and moves it. Against independent expectations: a damped run settles on the
// static hyperelastic answer with the end's displacement prescribed (fem/hyperelastic_static.hpp),
// whose reaction, summed from the elements over the held nodes, is the tool's force; a small motion
// gives the linear model's answer; the energy ledger E + D = W_loads + W_tools closes as dt^2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/hyperelastic_static.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "model/energy.hpp"
#include "model/fem_model.hpp"
#include "model/internal_force.hpp"

namespace roifem::model {
namespace {

/// A 60 x 20 x 20 mm block held at x = 0; a tool holds its x = 60 mm face and moves it by `lift`
/// on a smooth ramp (a linear ramp's kink leaves modes ringing that the trapezoidal rule, which
/// does not damp them numerically, keeps for seconds: 2e-5 of the answer after 4 s).
struct HeldCantilever {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  FemModel model;
  HeldCantilever(Vec3 lift, double alpha, double ramp, fem::MaterialModel law = fem::MaterialModel::neo_hookean) {
    fem::Material m = fem::Material::from_young_poisson(3000, 0.45, 1000, alpha);
    m.model = law;
    model =
        build_fem_model(mesh, m, {"x0"}, {},
                        {{.name = "hand", .set = "x1", .path = {.displacement = lift, .ramp = Ramp{ramp, Ramp::Shape::smooth}}}});
  }
  const SecondOrderSystem& sys() const { return model.system; }
};

/// The static neo-Hookean answer with the held face at `lift`: the free dofs' displacement, and
/// the face's reaction summed from the elements' forces (N).
struct StaticAnswer {
  Vector u_free;
  Vec3 reaction;
};

StaticAnswer static_answer(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const Vec3& lift) {
  fem::Constraints held(mesh.num_nodes());
  held.fix_set(mesh, "x0");
  for (const int n : mesh.set("x1").nodes) held.fix_node(n, lift);
  const fem::DofMap dofs(held);
  const fem::HyperelasticAssembler assembler(mesh, dofs, materials);
  fem::StaticLoadOptions options;
  options.max_increment = 0.1;
  const Vector u_free =
      fem::solve_hyperelastic_static(assembler, dofs, Vector::Zero(dofs.num_free()), {1.0}, options).back().u_free;
  // The reaction: every element's force at the held face's nodes (those nodes free in this map).
  fem::Constraints base_only(mesh.num_nodes());
  base_only.fix_set(mesh, "x0");
  const fem::DofMap unheld(base_only);
  Vector f(unheld.num_free());
  fem::HyperelasticAssembler(mesh, unheld, materials).force(dofs.expand(u_free), f);
  Vec3 reaction = Vec3::Zero();
  for (const int n : mesh.set("x1").nodes)
    for (int c = 0; c < 3; ++c) reaction[c] += f[unheld.free_dof(n, c)];
  return {u_free, reaction};
}

State run(const SecondOrderSystem& sys, integrators::Trapezoid& trapezoid, double t_end, EnergyLedger* ledger = nullptr,
          double* worst_balance = nullptr) {
  State s = State::at_rest(sys.size());
  trapezoid.reset(sys, s);
  const long steps = std::lround(t_end / trapezoid.dt());
  for (long k = 1; k <= steps; ++k) {
    trapezoid.advance_to(static_cast<double>(k) * trapezoid.dt(), s);
    if (ledger) {
      ledger->record(s);
      *worst_balance = std::max(*worst_balance, std::abs(ledger->balance_residual()));
    }
  }
  return s;
}

const Vec3 large_lift(0, 0.005, -0.015);  // 15 mm down and 5 mm sideways at the end of a 60 mm block

TEST(NonlinearTools, ADampedRunSettlesOnTheStaticAnswerAndTheToolFeelsItsReaction) {
  const HeldCantilever c(large_lift, 30.0, 0.5);
  ASSERT_TRUE(c.sys().is_nonlinear());
  ASSERT_TRUE(c.sys().internal_force->has_motion());
  integrators::Trapezoid trapezoid(0.02);
  const State s = run(c.sys(), trapezoid, 8.0);
  const StaticAnswer expected = static_answer(c.mesh, c.model.materials, large_lift);
  const double u_error = (s.u - expected.u_free).lpNorm<Eigen::Infinity>() / expected.u_free.lpNorm<Eigen::Infinity>();
  const Vec3 F = c.model.tools.forces(s.u, s.t).head<3>();
  const double F_error = (F - expected.reaction).norm() / expected.reaction.norm();
  // The linear model's answer, for scale: how nonlinear the motion is.
  const HeldCantilever linear(large_lift, 30.0, 0.5, fem::MaterialModel::linear);
  integrators::Trapezoid linear_trapezoid(0.02);
  const State s_lin = run(linear.sys(), linear_trapezoid, 8.0);
  const Vec3 F_lin = linear.model.tools.forces(s_lin.u, s_lin.t).head<3>();
  std::printf(
      "held end moved (0, 5, -15) mm: |u - u_static| / |u_static| = %.2e, |F - reaction| / |reaction| = %.2e; "
      "F = (%.4f, %.4f, %.4f) N, the linear model's (%.4f, %.4f, %.4f) N\n",
      u_error, F_error, F.x(), F.y(), F.z(), F_lin.x(), F_lin.y(), F_lin.z());
  EXPECT_LT(u_error, 1e-6);
  EXPECT_LT(F_error, 1e-6);
  EXPECT_GT((F - F_lin).norm(), 0.05 * F_lin.norm()) << "a large motion that the linear model gets wrong";
}

TEST(NonlinearTools, ASmallMotionGivesTheLinearAnswer) {
  std::vector<double> differences;
  for (const double scale : {1e-3, 1e-5}) {
    const Vec3 lift = scale * large_lift;
    const HeldCantilever c(lift, 5.0, 0.3), linear(lift, 5.0, 0.3, fem::MaterialModel::linear);
    integrators::Trapezoid a(0.01), b(0.01);
    const State s = run(c.sys(), a, 0.6), s_lin = run(linear.sys(), b, 0.6);
    const double u_difference = (s.u - s_lin.u).lpNorm<Eigen::Infinity>() / s_lin.u.lpNorm<Eigen::Infinity>();
    const Vector F = c.model.tools.forces(s.u, s.t), F_lin = linear.model.tools.forces(s_lin.u, s_lin.t);
    const double F_difference = (F - F_lin).norm() / F_lin.norm();
    std::printf("motion %.0e of the large one: u differs from the linear model's by %.2e, F by %.2e\n", scale, u_difference,
                F_difference);
    differences.push_back(F_difference);
    EXPECT_LT(u_difference, scale);
    EXPECT_LT(F_difference, scale);
  }
  // First order in the motion: 100 times smaller, 100 times closer.
  EXPECT_NEAR(std::log10(differences[0] / differences[1]), 2.0, 0.05);
}

TEST(NonlinearTools, TheEnergyLedgerWithTheToolsWorkClosesAsDtSquared) {
  std::vector<double> residuals;
  for (const double dt : {0.01, 0.005}) {
    const HeldCantilever c(large_lift, 0.0, 0.3);  // undamped: the tool's work goes into E alone
    integrators::Trapezoid trapezoid(dt);
    State s0 = State::at_rest(c.sys().size());
    EnergyLedger ledger(c.sys(), s0, &c.model.tools);
    double worst = 0;
    run(c.sys(), trapezoid, 0.6, &ledger, &worst);
    residuals.push_back(worst / std::abs(ledger.tool_work()));
    std::printf("dt = %.3f s: max |E + D - W - W_tools - E0| / W_tools = %.3e (W_tools %.3e J, E %.3e J)\n", dt, residuals.back(),
                ledger.tool_work(), ledger.total());
    EXPECT_GT(ledger.tool_work(), 0.0);
  }
  EXPECT_LT(residuals.back(), 1e-2);
  EXPECT_NEAR(std::log2(residuals[0] / residuals[1]), 2.0, 0.4) << "the rule's O(dt^2) energy error";
}

}  // namespace
}  // namespace roifem::model
