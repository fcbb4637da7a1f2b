// SPDX-License-Identifier: GPL-3.0-or-later
// The seam's divergence check (integrators/integrator.hpp, model/energy_bound.hpp): the bound it
// holds every method to is a bound of the exact solution (checked against the modal solution and
// the trapezoidal rule's discrete energy), and every explicit method at a fixed step past its
// stability limit stops with a SolverError naming the method, the time and the step, long before
// its numbers overflow, while the same method inside its limit runs to the end.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/stability.hpp"
#include "model/energy_bound.hpp"
#include "model/modal_reference.hpp"
#include "test_problems.hpp"

namespace roifem::integrators {
namespace {

using test_problems::Cantilever;

TEST(EnergyBound, BoundsTheExactSolutionAndTheTrapezoidalRule) {
  const Cantilever c(-0.02, 0.1);
  const model::State rest = c.rest();
  model::EnergyBound bound(c.sys(), rest);
  const model::ModalReference exact(c.sys(), rest);
  auto trapezoid = make_integrator("trapezoid", 0.002);
  model::State s = rest;
  trapezoid->reset(c.sys(), s);
  double tightest = 0;  // the largest ||v||_M / bound seen: the bound must hold, and not be loose beyond use
  for (int k = 1; k <= 500; ++k) {
    const double t = 0.002 * k;
    const model::State truth{t, exact.displacement(t), exact.velocity(t)};
    const double ratio = bound.velocity_norm(truth) / bound.velocity_norm_bound(t);
    EXPECT_LE(ratio, 1.0) << "the exact solution leaves the bound at t = " << t;
    tightest = std::max(tightest, ratio);
    trapezoid->advance_to(t, s);
    EXPECT_LE(bound.velocity_norm(s), bound.velocity_norm_bound(t) * (1 + 1e-12)) << "the trapezoidal rule at t = " << t;
  }
  EXPECT_GT(tightest, 0.05) << "a bound this loose would let a divergence run on";
}

TEST(EnergyBound, CountsTheInitialEnergy) {
  const auto sys = test_problems::damped_oscillator();  // no load: sqrt(2 E_0) = sqrt(K) u_0 throughout
  model::EnergyBound bound(sys, test_problems::oscillator_start());
  EXPECT_NEAR(bound.velocity_norm_bound(0.0), 5e-3, 1e-15);
  EXPECT_NEAR(bound.velocity_norm_bound(10.0), 5e-3, 1e-15);
}

/// The explicit methods that take a fixed step, from the table.
std::vector<const IntegratorInfo*> explicit_fixed_step_methods() {
  std::vector<const IntegratorInfo*> rows;
  for (const auto& info : integrator_table())
    if (info.is_explicit && info.fixed_step) rows.push_back(&info);
  return rows;
}

TEST(IntegratorSeam, EveryExplicitFixedStepMethodPastItsLimitStopsNamingTheStep) {
  const Cantilever c(-0.02, 0.1);
  const auto fixed_step = explicit_fixed_step_methods();
  ASSERT_GE(fixed_step.size(), 5u);  // arkode-erk2..5, gsl-rk4
  for (const IntegratorInfo* info : fixed_step) {
    // The paper's step, far beyond every explicit method's limit on this model (w_max ~ 1e4 rad/s).
    auto integrator = make_integrator(info->name, 0.05);
    model::State s = c.rest();
    integrator->reset(c.sys(), s);
    try {
      for (int k = 1; k <= 200; ++k) integrator->advance_to(0.05 * k, s);
      ADD_FAILURE() << info->name << " ran 200 steps past its stability limit without a word (max |u| "
                    << s.u.lpNorm<Eigen::Infinity>() << " m)";
    } catch (const SolverError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(info->name + ": the solution diverged (", 0), 0u) << what;
      std::smatch at;
      ASSERT_TRUE(std::regex_search(what, at, std::regex(R"(\) by t = ([0-9.]+) s, step ([0-9]+);)"))) << what;
      EXPECT_LE(std::stod(at[1]), 0.25) << what;  // within five steps: long before the numbers overflow
      EXPECT_LE(std::stol(at[2]), 5) << what;
      EXPECT_NE(what.find("time.dt_s"), std::string::npos) << what;
    }
  }
}

TEST(IntegratorSeam, EveryExplicitFixedStepMethodInsideItsLimitRunsToTheEnd) {
  const Cantilever c(-0.02, 0.1);
  const model::ModalReference exact(c.sys(), c.rest());
  for (const IntegratorInfo* info : explicit_fixed_step_methods()) {
    const double limit = predicted_stability_limit(*info, exact.frequencies(), exact.alpha());
    ASSERT_TRUE(std::isfinite(limit)) << info->name;
    const double dt = 0.2 / std::ceil(0.2 / (0.5 * limit));  // half the limit, on the grid of 0.2 s
    auto integrator = make_integrator(info->name, dt);
    model::State s = c.rest();
    integrator->reset(c.sys(), s);
    EXPECT_NO_THROW(integrator->advance_to(0.2, s)) << info->name << " at dt = " << dt;
  }
}

TEST(IntegratorSeam, ANonFiniteStateIsADivergence) {
  auto sys = test_problems::damped_oscillator();
  sys.load.add(Vector::Constant(1, HUGE_VAL), model::Ramp{0.0});  // an infinite force: no energy bound, inf in the state
  auto integrator = make_integrator("trapezoid", 0.01);
  model::State s = test_problems::oscillator_start();
  integrator->reset(sys, s);
  try {
    integrator->advance_to(0.01, s);
    FAIL() << "a non-finite state passed";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("trapezoid: the solution diverged (non-finite values) by t = 0.01 s, step 1"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace roifem::integrators
