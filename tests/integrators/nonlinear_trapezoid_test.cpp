// SPDX-License-Identifier: GPL-3.0-or-later
// The trapezoidal rule on a nonlinear (neo-Hookean) model (integrators/trapezoid_newton.hpp),
// against independent expectations: Newton converges quadratically; a damped run settles on the
// static neo-Hookean answer (fem/hyperelastic_static.hpp, itself checked against CalculiX); an
// explicit ARKODE run at tight tolerance on the same ODE agrees with it, and the gap shrinks as dt^2;
// at small load the linear trajectory is recovered; the energy ledger balances with W(u).
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "fem/hyperelastic_static.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/neo_hookean_cantilever.hpp"
#include "integrators/trapezoid.hpp"
#include "model/energy.hpp"
#include "model/internal_force.hpp"

namespace roifem::integrators {
namespace {

using testing::bending_force;
using testing::NeoHookeanCantilever;
using testing::run_until;

TEST(NonlinearTrapezoid, IsAGenuinelyNonlinearProblem) {
  const NeoHookeanCantilever c(5.0, bending_force, 0.5);
  ASSERT_TRUE(c.sys().is_nonlinear());
  Trapezoid trapezoid(0.01);
  const model::State s = run_until(c.sys(), trapezoid, 1.0, 0.01);
  const NeoHookeanCantilever linear(5.0, bending_force, 0.5, fem::MaterialModel::linear);
  Trapezoid linear_trapezoid(0.01);
  const model::State s_lin = run_until(linear.sys(), linear_trapezoid, 1.0, 0.01);
  std::printf("tip drop at 1 s: neo-Hookean %.3f mm, linear %.3f mm (beam length 60 mm)\n", 1e3 * c.tip_drop(s),
              1e3 * linear.tip_drop(s_lin));
  EXPECT_GT(c.tip_drop(s), 0.1 * 0.06);
  EXPECT_GT(std::abs(c.tip_drop(s) - linear.tip_drop(s_lin)), 0.02 * linear.tip_drop(s_lin));
}

TEST(NonlinearTrapezoid, NewtonConvergesQuadratically) {
  const NeoHookeanCantilever c(5.0, bending_force, 0.0);  // the whole load at once: a hard first step
  Trapezoid trapezoid(0.02);
  model::State s = model::State::at_rest(c.sys().size());
  trapezoid.reset(c.sys(), s);
  // The step's Newton history, reproduced by the same equation outside the integrator.
  const model::AverageAcceleration rule(0.02);
  TrapezoidNewton newton(c.sys(), rule);
  // The history term as the rule forms it: b = f_1 + M w_0 (a_0 = M^-1 f_0: the load is a step).
  const Vector a0 = model::AverageAcceleration::consistent_acceleration(c.sys(), s);
  Vector b = c.sys().load.at(0.02), w(c.sys().size());
  rule.history(c.sys(), s, a0, b, w);
  b += c.sys().M * w;
  Vector u = Vector::Zero(c.sys().size());  // the integrator's predictor: u_0
  const auto report = newton.solve(0.02, b, u, b.lpNorm<Eigen::Infinity>());
  std::printf("Newton on the first step (residual / load):");
  for (const auto& it : report.history) std::printf(" %.2e", it.residual / b.lpNorm<Eigen::Infinity>());
  std::printf("\n");
  ASSERT_GE(report.iterations(), 3);
  int quadratic_pairs = 0;
  for (std::size_t k = 1; k + 1 < report.history.size(); ++k) {
    const double r0 = report.history[k].residual / b.lpNorm<Eigen::Infinity>();
    const double r1 = report.history[k + 1].residual / b.lpNorm<Eigen::Infinity>();
    if (r0 > 1e-2 || r1 < 1e-11) continue;  // outside the asymptotic range, or at rounding
    EXPECT_GT(std::log(r1) / std::log(r0), 1.7) << "residual " << r0 << " -> " << r1;
    ++quadratic_pairs;
  }
  EXPECT_GE(quadratic_pairs, 1);
  trapezoid.advance_to(0.02, s);
  EXPECT_LT((s.u - u).norm(), 1e-12 * u.norm()) << "the integrator's step is the same Newton solve";
  EXPECT_EQ(trapezoid.stats().nonlinear_iterations, report.iterations());
}

TEST(NonlinearTrapezoid, ADampedRunSettlesOnTheStaticNeoHookeanAnswer) {
  const NeoHookeanCantilever c(20.0, bending_force, 0.5);
  Trapezoid trapezoid(0.02);
  const model::State s = run_until(c.sys(), trapezoid, 4.0, 0.02);
  const fem::HyperelasticAssembler assembler(c.mesh, *c.model.dofs, c.model.materials);
  const Vector u_static = fem::solve_hyperelastic_static(assembler, *c.model.dofs, c.sys().load.at(10.0), {1.0}).back().u_free;
  const double difference = (s.u - u_static).lpNorm<Eigen::Infinity>() / u_static.lpNorm<Eigen::Infinity>();
  std::printf("damped run at 4 s against the static answer: %.2e (peak %.3f mm); %ld Newton iterations in %ld steps\n",
              difference, 1e3 * u_static.lpNorm<Eigen::Infinity>(), trapezoid.stats().nonlinear_iterations,
              trapezoid.stats().steps);
  EXPECT_LT(difference, 1e-6);
}

TEST(NonlinearTrapezoid, AgreesWithATightExplicitArkodeRunToSecondOrder) {
  // A smooth ramp: a linear one's kinks excite modes with omega dt > 1, where no rule is in its
  // asymptotic range.
  const NeoHookeanCantilever c(2.0, bending_force, 0.3, fem::MaterialModel::neo_hookean, model::Ramp::Shape::smooth);
  const double t_end = 0.5;
  // Its first step is its output interval: 1 ms keeps the first stages' elements upright.
  auto reference_method =
      make_integrator("arkode-erk5", StepControl{.dt = 0.001, .adaptive = true, .rtol = 1e-10, .atol = 1e-14});
  ASSERT_TRUE(reference_method->takes_nonlinear());
  const model::State reference = run_until(c.sys(), *reference_method, t_end, 0.001);
  std::vector<double> errors;
  for (const double dt : {0.01, 0.005, 0.0025}) {
    Trapezoid trapezoid(dt);
    const model::State s = run_until(c.sys(), trapezoid, t_end, dt);
    errors.push_back((s.u - reference.u).lpNorm<Eigen::Infinity>() / reference.u.lpNorm<Eigen::Infinity>());
    std::printf("dt = %.4f s: max |u - u_erk5| / max |u_erk5| = %.3e\n", dt, errors.back());
  }
  EXPECT_LT(errors.back(), 1e-3);
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    EXPECT_NEAR(order, 2.0, 0.3) << "observed order between dt and dt/2";
  }
}

TEST(NonlinearTrapezoid, SmallLoadFollowsTheLinearTrajectory) {
  const double small = bending_force * 1e-4;
  const NeoHookeanCantilever c(2.0, small, 0.3), linear(2.0, small, 0.3, fem::MaterialModel::linear);
  Trapezoid a(0.01), b(0.01);
  const model::State s = run_until(c.sys(), a, 0.5, 0.01), s_lin = run_until(linear.sys(), b, 0.5, 0.01);
  const double difference = (s.u - s_lin.u).lpNorm<Eigen::Infinity>() / s_lin.u.lpNorm<Eigen::Infinity>();
  std::printf("load 1e-4 of full: |u_nl - u_lin| / |u_lin| = %.2e\n", difference);
  EXPECT_LT(difference, 1e-3);
}

TEST(NonlinearTrapezoid, EnergyLedgerBalancesWithTheStrainEnergyW) {
  const NeoHookeanCantilever c(2.0, bending_force, 0.3);
  Trapezoid trapezoid(0.005);
  model::State s = model::State::at_rest(c.sys().size());
  trapezoid.reset(c.sys(), s);
  model::EnergyLedger ledger(c.sys(), s);
  double worst = 0;
  for (int k = 1; k <= 200; ++k) {
    trapezoid.advance_to(0.005 * k, s);
    ledger.record(s);
    worst = std::max(worst, std::abs(ledger.balance_residual()) / ledger.external_work());
  }
  // The trapezoidal rule balances energy exactly only for a linear system (Simo & Tarnow 1992);
  // here the imbalance is the rule's O(dt^2) error, not rounding.
  std::printf("nonlinear, damped, loaded: max |E + D - W - E0| / W = %.3e, W(u) at the end %.3e J\n", worst, ledger.strain());
  EXPECT_LT(worst, 2e-2);
  EXPECT_NEAR(ledger.strain(), c.sys().internal_force->energy(s.t, s.u), 1e-15);
}

TEST(NonlinearTrapezoid, AnInvertingStepIsNamedWithItsStepAndTime) {
  const NeoHookeanCantilever c(0.0, 50.0, 0.0);  // 2500 times the load, all at once
  Trapezoid trapezoid(0.05);
  try {
    run_until(c.sys(), trapezoid, 0.1, 0.05);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("trapezoid: step 1, t = 0.05 s:"), std::string::npos) << what;
    EXPECT_TRUE(what.find("has inverted") != std::string::npos || what.find("did not converge") != std::string::npos ||
                what.find("not positive definite") != std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace roifem::integrators
