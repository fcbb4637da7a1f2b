// SPDX-License-Identifier: GPL-3.0-or-later
// The energy-momentum method (integrators/energy_momentum.hpp) against independent expectations:
// on the neo-Hookean cantilever its energy ledger (model/energy.hpp, which knows nothing of the
// method) balances to the Newton tolerance, damped or not, where the trapezoidal rule's does not;
// an undamped free vibration keeps its energy over many periods at a step far beyond the period's
// resolution; a tight explicit ARKODE run agrees with it at second order; on a linear model it is
// the trapezoidal rule.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "common/errors.hpp"
#include "integrators/energy_momentum.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/neo_hookean_cantilever.hpp"
#include "integrators/trapezoid.hpp"
#include "model/energy.hpp"

namespace roifem::integrators {
namespace {

using testing::bending_force;
using testing::NeoHookeanCantilever;
using testing::run_until;

/// The worst |E + D - W - E_0| over a run of `steps` steps of `dt`, relative to the loads' work.
double worst_energy_imbalance(const model::SecondOrderSystem& sys, Integrator& method, double dt, int steps) {
  model::State s = model::State::at_rest(sys.size());
  method.reset(sys, s);
  model::EnergyLedger ledger(sys, s);
  double worst = 0;
  for (int k = 1; k <= steps; ++k) {
    method.advance_to(dt * k, s);
    ledger.record(s);
    worst = std::max(worst, std::abs(ledger.balance_residual()) / ledger.external_work());
  }
  return worst;
}

TEST(EnergyMomentumMethod, TheLedgerBalancesToTheNewtonToleranceWhereTheTrapezoidalRulesDoesNot) {
  for (const double alpha : {0.0, 2.0}) {
    const NeoHookeanCantilever c(alpha, bending_force, 0.3);
    ASSERT_TRUE(c.sys().is_nonlinear());
    EnergyMomentum em(0.005);
    Trapezoid trapezoid(0.005);
    const double em_worst = worst_energy_imbalance(c.sys(), em, 0.005, 200);
    const double trapezoid_worst = worst_energy_imbalance(c.sys(), trapezoid, 0.005, 200);
    std::printf(
        "alpha = %.0f 1/s, dt = 5 ms, 1 s: max |E + D - W - E0| / W: energy-momentum %.2e, trapezoid %.2e; "
        "%ld Newton iterations in %ld steps\n",
        alpha, em_worst, trapezoid_worst, em.stats().nonlinear_iterations, em.stats().steps);
    EXPECT_LT(em_worst, 1e-12);
    EXPECT_GT(trapezoid_worst, 100 * em_worst) << "the problem must be one the trapezoidal rule does not balance";
  }
}

TEST(EnergyMomentumMethod, AnUndampedFreeVibrationKeepsItsEnergyAtALargeStep) {
  // The load rises for 0.05 s and falls for as long (a sampled hat):
  // from then on E must stay at its value, over about 40 periods of the first mode.
  NeoHookeanCantilever c(0.0, bending_force, 0.0);
  const auto hat = std::make_shared<const model::Ramp::Samples>(model::Ramp::Samples{{0, 0.05, 0.1}, {0, 1, 0}});
  c.model.system.load = c.sys().load.with_ramp(model::Ramp::sampled(hat));
  const double dt = 0.02;  // about a sixth of the first period: far from resolving the stiff modes
  EnergyMomentum em(dt);
  Trapezoid trapezoid(dt);
  for (Integrator* method : {static_cast<Integrator*>(&em), static_cast<Integrator*>(&trapezoid)}) {
    model::State s = model::State::at_rest(c.sys().size());
    method->reset(c.sys(), s);
    model::EnergyLedger ledger(c.sys(), s);
    double E_free = 0, drift = 0;
    for (int k = 1; k <= 250; ++k) {
      method->advance_to(dt * k, s);
      ledger.record(s);
      if (k * dt < 0.1 + 1e-12) continue;
      if (E_free == 0) E_free = ledger.total();
      drift = std::max(drift, std::abs(ledger.total() - E_free) / E_free);
    }
    std::printf("%-16s undamped, free after 0.1 s, dt = 20 ms, 5 s: E %.4e J, max |E - E_free| / E_free %.2e\n",
                std::string(method->name()).c_str(), E_free, drift);
    if (method == &em) {
      EXPECT_LT(drift, 1e-12);
    } else {
      EXPECT_GT(drift, 1e-6) << "the trapezoidal rule's drift on this problem: what the method is for";
    }
  }
}

TEST(EnergyMomentumMethod, AgreesWithATightExplicitArkodeRunToSecondOrder) {
  const NeoHookeanCantilever c(2.0, bending_force, 0.3, fem::MaterialModel::neo_hookean, model::Ramp::Shape::smooth);
  const double t_end = 0.5;
  auto reference_method =
      make_integrator("arkode-erk5", StepControl{.dt = 0.001, .adaptive = true, .rtol = 1e-10, .atol = 1e-14});
  const model::State reference = run_until(c.sys(), *reference_method, t_end, 0.001);
  std::vector<double> errors;
  for (const double dt : {0.01, 0.005, 0.0025}) {
    EnergyMomentum em(dt);
    const model::State s = run_until(c.sys(), em, t_end, dt);
    errors.push_back((s.u - reference.u).lpNorm<Eigen::Infinity>() / reference.u.lpNorm<Eigen::Infinity>());
    std::printf("energy-momentum dt = %.4f s: max |u - u_erk5| / max |u_erk5| = %.3e (%ld Newton iterations)\n", dt,
                errors.back(), em.stats().nonlinear_iterations);
  }
  EXPECT_LT(errors.back(), 1e-3);
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_NEAR(std::log2(errors[k - 1] / errors[k]), 2.0, 0.3);
}

TEST(EnergyMomentumMethod, OnALinearModelItIsTheTrapezoidalRule) {
  const NeoHookeanCantilever c(5.0, bending_force, 0.3, fem::MaterialModel::linear);
  ASSERT_FALSE(c.sys().is_nonlinear());
  EnergyMomentum em(0.01);
  Trapezoid trapezoid(0.01);
  const model::State a = run_until(c.sys(), em, 1.0, 0.01);
  const model::State b = run_until(c.sys(), trapezoid, 1.0, 0.01);
  const double difference = (a.u - b.u).lpNorm<Eigen::Infinity>() / b.u.lpNorm<Eigen::Infinity>();
  std::printf("linear: |u_em - u_trapezoid| / |u_trapezoid| = %.2e\n", difference);
  EXPECT_LT(difference, 1e-9);
  EXPECT_LT((a.v - b.v).lpNorm<Eigen::Infinity>(), 1e-9 * b.v.lpNorm<Eigen::Infinity>());
}

TEST(EnergyMomentumMethod, IsInTheTableAsANonlinearMethodOnly) {
  EXPECT_EQ(integrator_order("energy-momentum"), 2);
  auto method = make_integrator("energy-momentum", 0.01);
  EXPECT_TRUE(method->takes_nonlinear());
  EXPECT_EQ(method->name(), "energy-momentum");
}

TEST(EnergyMomentumMethod, AnInvertingStepIsNamedWithItsStepAndTime) {
  const NeoHookeanCantilever c(0.0, 50.0, 0.0);  // 2500 times the load, all at once
  EnergyMomentum em(0.05);
  try {
    run_until(c.sys(), em, 0.1, 0.05);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("energy-momentum: step 1, t = 0.05 s:"), std::string::npos) << what;
  }
}

TEST(EnergyMomentumMethod, RefusesANonPositiveStep) {
  EXPECT_THROW(EnergyMomentum(0.0), InputError);
  EXPECT_THROW(EnergyMomentum(-1e-3), InputError);
  EXPECT_THROW(EnergyMomentum(std::nan("")), InputError);
}

}  // namespace
}  // namespace roifem::integrators
