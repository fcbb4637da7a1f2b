// SPDX-License-Identifier: GPL-3.0-or-later
// Newton in every implicit family on a nonlinear (neo-Hookean) model: ARKODE's DIRK methods and
// IDA's BDF, with the Jacobian from the tangent K_t(u) (integrators/arkode.hpp, ida.hpp), against
// independent expectations: each agrees with a tight explicit ARKODE run (which needs no
// Jacobian) to its tolerance; ARKODE's trapezoid table at a fixed step is the hand-written
// trapezoidal rule (Newmark average acceleration by Newton, integrators/trapezoid_newton.hpp) on
// the same equation; SDIRK-2 at a fixed step converges at order 2. Methods that take no nonlinear
// model refuse it by name, and the table says the same as the methods.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/neo_hookean_cantilever.hpp"
#include "integrators/trapezoid.hpp"

namespace roifem::integrators {
namespace {

using testing::bending_force;
using testing::NeoHookeanCantilever;
using testing::run_until;

// A smooth ramp: a linear one's kinks excite modes that no step here resolves.
const NeoHookeanCantilever& smooth_cantilever() {
  static const NeoHookeanCantilever c(2.0, bending_force, 0.3, fem::MaterialModel::neo_hookean, model::Ramp::Shape::smooth);
  return c;
}
constexpr double smooth_run_end = 0.5;

/// The reference: explicit Dormand-Prince 5(4) at rtol 1e-10, which uses f_int alone.
const model::State& erk5_reference() {
  static const model::State s = [] {
    auto erk5 = make_integrator("arkode-erk5", StepControl{.dt = 0.001, .adaptive = true, .rtol = 1e-10, .atol = 1e-14});
    return run_until(smooth_cantilever().sys(), *erk5, smooth_run_end, 0.001);
  }();
  return s;
}

double error_against_erk5(const model::State& s) {
  return (s.u - erk5_reference().u).lpNorm<Eigen::Infinity>() / erk5_reference().u.lpNorm<Eigen::Infinity>();
}

TEST(NonlinearImplicit, EveryImplicitFamilyAgreesWithATightExplicitRun) {
  const model::SecondOrderSystem& sys = smooth_cantilever().sys();
  ASSERT_TRUE(sys.is_nonlinear());
  std::printf("%-20s %8s %8s %10s %8s %8s %10s\n", "method", "steps", "Newton", "Newton/st", "Jacobians", "setups", "error");
  for (const char* name : {"arkode-esdirk4", "arkode-esdirk4-mass", "arkode-esdirk5", "ida-bdf5", "ida-bdf2"}) {
    auto method = make_integrator(name, StepControl{.dt = 0.01, .adaptive = true, .rtol = 1e-8, .atol = 1e-12});
    ASSERT_TRUE(method->takes_nonlinear()) << name;
    const model::State s = run_until(sys, *method, smooth_run_end, 0.01);
    const Stats st = method->stats();
    const double error = error_against_erk5(s);
    std::printf("%-20s %8ld %8ld %10.2f %8ld %8ld %10.2e\n", name, st.steps, st.nonlinear_iterations,
                static_cast<double>(st.nonlinear_iterations) / static_cast<double>(st.steps), st.jac_evals, st.lin_setups, error);
    EXPECT_LT(error, 2e-5) << name;
    // Newton really iterated on a Jacobian that moves: more iterations than steps, and the
    // Jacobian rebuilt from the tangent more than once.
    EXPECT_GT(st.nonlinear_iterations, st.steps) << name;
    EXPECT_GT(st.jac_evals, 1) << name;
  }
}

TEST(NonlinearImplicit, GslsImplicitSteppersTakeTheTangentAsTheirJacobian) {
  // GSL's implicit steppers iterate on the dense Jacobian they ask for, here -M^-1 K_t(u) at the
  // state they ask at; GSL counts no Newton iterations, only the Jacobians.
  const model::SecondOrderSystem& sys = smooth_cantilever().sys();
  // msbdf adaptive at rtol 1e-8; rk4imp (implicit Gauss-Legendre, order 4) at a fixed 5 ms.
  for (const auto& [name, adaptive, tolerance] : {std::tuple{"gsl-msbdf", true, 2e-5}, std::tuple{"gsl-rk4imp", false, 1e-4}}) {
    auto method =
        make_integrator(name, StepControl{.dt = adaptive ? 0.01 : 0.005, .adaptive = adaptive, .rtol = 1e-8, .atol = 1e-12});
    ASSERT_TRUE(method->takes_nonlinear()) << name;
    const model::State s = run_until(sys, *method, smooth_run_end, 0.01);
    const Stats st = method->stats();
    const double error = error_against_erk5(s);
    std::printf("%-12s %6ld steps, %6ld Jacobians, %8ld right-hand sides: %.2e of the peak from ERK5\n", name, st.steps,
                st.jac_evals, st.rhs_evals, error);
    EXPECT_LT(error, tolerance) << name;
    EXPECT_GT(st.jac_evals, 1) << name << ": the Jacobian moves with u";
  }
}

TEST(NonlinearImplicit, ArkodesTrapezoidTableIsTheHandWrittenTrapezoidalRule) {
  // Two codes, one rule: ARKODE's user table c = [0, 1], A = [[0, 0], [1/2, 1/2]] on y = [u; v]
  // and Newmark's average acceleration on M u'' + C u' + f_int(u) = f. They differ only by their
  // Newton tolerances.
  const model::SecondOrderSystem& sys = smooth_cantilever().sys();
  const double dt = 0.005;
  auto arkode = make_integrator("arkode-trapezoid", StepControl{.dt = dt, .rtol = 1e-10, .atol = 1e-14});
  Trapezoid hand_written(dt);
  const model::State a = run_until(sys, *arkode, smooth_run_end, dt), b = run_until(sys, hand_written, smooth_run_end, dt);
  const double difference = (a.u - b.u).lpNorm<Eigen::Infinity>() / b.u.lpNorm<Eigen::Infinity>();
  std::printf(
      "arkode-trapezoid against trapezoid at dt = %.3f s: %.2e of the peak (each %.2e from the reference); "
      "Newton iterations %ld against %ld, Jacobians %ld\n",
      dt, difference, error_against_erk5(b), arkode->stats().nonlinear_iterations, hand_written.stats().nonlinear_iterations,
      arkode->stats().jac_evals);
  EXPECT_LT(difference, 1e-6);
  EXPECT_GT(error_against_erk5(b), 100 * difference) << "the agreement is closer than the rule's own error";
}

TEST(NonlinearImplicit, Sdirk2AtAFixedStepConvergesAtOrderTwo) {
  const model::SecondOrderSystem& sys = smooth_cantilever().sys();
  std::vector<double> errors;
  for (const double dt : {0.01, 0.005, 0.0025}) {
    auto sdirk2 = make_integrator("arkode-sdirk2", StepControl{.dt = dt, .rtol = 1e-8, .atol = 1e-12});
    errors.push_back(error_against_erk5(run_until(sys, *sdirk2, smooth_run_end, dt)));
    std::printf("arkode-sdirk2, dt = %.4f s: %.3e of the peak\n", dt, errors.back());
  }
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_NEAR(std::log2(errors[k - 1] / errors[k]), 2.0, 0.3);
}

TEST(NonlinearImplicit, AFixedStepWhoseNewtonFailsIsNamedWithItsTime) {
  const NeoHookeanCantilever c(0.0, 50.0, 0.0);  // 1700 times the load, all at once
  auto method = make_integrator("arkode-sdirk2", StepControl{.dt = 0.05});
  try {
    run_until(c.sys(), *method, 0.1, 0.05);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("arkode-sdirk2: failed at t = 0"), std::string::npos) << what;
    EXPECT_NE(what.find("has inverted"), std::string::npos) << what;
  }
}

TEST(NonlinearIntegrators, AMethodThatTakesNoNonlinearModelRefusesItByName) {
  const NeoHookeanCantilever c(2.0, bending_force, 0.3);
  for (const char* name : {"arkode-sdirk2-schur", "arkode-esdirk4-mass-schur", "trapezoid-cg"}) {
    auto method = make_integrator(name, 0.01);
    try {
      method->reset(c.sys(), model::State::at_rest(c.sys().size()));
      FAIL() << name << " took it";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string(name) + " does not take a nonlinear model (neo-hookean, every element)"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(NonlinearIntegrators, TheTablesNonlinearColumnIsWhatEachMethodTakes) {
  int nonlinear = 0;
  for (const IntegratorInfo& row : integrator_table()) {
    const auto method = make_integrator(row, StepControl{.dt = 0.01});
    EXPECT_EQ(row.nonlinear, method->takes_nonlinear()) << row.name;
    nonlinear += row.nonlinear;
  }
  // the trapezoid, the explicit methods, ARKODE's implicit ones on KLU, IDA and GSL's
  EXPECT_GE(nonlinear, 20);
}

}  // namespace
}  // namespace roifem::integrators
