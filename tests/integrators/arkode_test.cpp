// SPDX-License-Identifier: GPL-3.0-or-later
// ARKODE's methods (arkode.hpp): the trapezoid's Butcher table against the hand-written rule, the
// observed order of every method, adaptive tolerances, and the messages of a failed run.
#include "integrators/arkode.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/test_problems.hpp"
#include "integrators/trapezoid.hpp"
#include "model/modal_reference.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::integrators {
namespace {

using test_problems::Cantilever;
using test_problems::observed_order;
using test_problems::run;

TEST(Arkode, TrapezoidButcherTableEqualsTheHandWrittenRule) {
  const Cantilever c(1e-3, 0.3);
  Trapezoid hand(0.01);
  const Vector a = run(hand, c.sys(), c.rest(), 0.5);
  for (const char* name :
       {"arkode-trapezoid", "arkode-trapezoid-schur", "arkode-trapezoid-mass", "arkode-trapezoid-mass-schur"}) {
    auto table = make_integrator(name, 0.01);
    const Vector b = run(*table, c.sys(), c.rest(), 0.5);
    std::printf("hand-written vs %s: relative difference %.2e\n", name, (a - b).norm() / a.norm());
    EXPECT_LT((a - b).norm() / a.norm(), 1e-9) << name;
  }
}

// The same on a condensed paper model (split stiffness, dense interface block), over 200 steps
// at the paper's dt: the Schur solver's elimination and the K u cache change nothing.
TEST(Arkode, TrapezoidTableEqualsTheHandWrittenRuleOnTheCondensedPaperModel) {
  const auto model =
      simulation::build_scenario_model(scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup1.toml"));
  const auto& sys = model->system();
  const model::State rest = model::State::at_rest(sys.size());
  Trapezoid hand(0.05);
  const Vector a = run(hand, sys, rest, 10.0);
  for (const char* name : {"arkode-trapezoid", "arkode-trapezoid-schur"}) {
    auto table = make_integrator(name, 0.05);
    const Vector b = run(*table, sys, rest, 10.0);
    std::printf("setup 1, 200 steps: hand-written vs %s: relative difference %.2e\n", name, (a - b).norm() / a.norm());
    EXPECT_LT((a - b).norm() / a.norm(), 1e-9) << name;
  }
}

TEST(Arkode, MassMatrixVariantAgreesWithTheLumpedInverse) {
  const Cantilever c(1e-3, 0.3);
  auto lumped = make_integrator("arkode-esdirk4", 0.01);
  auto mass = make_integrator("arkode-esdirk4-mass", 0.01);
  const Vector a = run(*lumped, c.sys(), c.rest(), 0.5), b = run(*mass, c.sys(), c.rest(), 0.5);
  EXPECT_LT((a - b).norm() / a.norm(), 1e-9);
}

const char* const methods[] = {"arkode-erk2", "arkode-erk3",    "arkode-erk4",    "arkode-erk5",      "arkode-sdirk2",
                               "arkode-ark3", "arkode-esdirk4", "arkode-esdirk5", "arkode-trapezoid", "trapezoid"};

TEST(Arkode, EveryMethodShowsItsOrderOnADampedOscillator) {
  const model::SecondOrderSystem s = test_problems::damped_oscillator();
  const model::State start = test_problems::oscillator_start();
  const Vector exact = model::ModalReference(s, start).displacement(2.0);
  for (const char* method : methods) {
    const double order = observed_order(method, s, start, exact, 2.0, {0.02, 0.01, 0.005});
    EXPECT_NEAR(order, integrator_order(method), 0.3) << method;
  }
}

TEST(Arkode, EveryMethodShowsItsOrderOnAMeshAgainstTheModalSolution) {
  const Cantilever c(0, 0);
  // Start from three modes, the lowest and two faster ones (so that fifth-order errors stay above
  // round-off at steps the explicit methods can take: 4 dt <= 1 / w_max).
  const Vector m = DenseMatrix(c.sys().M).diagonal();
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(m.cwiseSqrt().cwiseInverse().asDiagonal() * DenseMatrix(c.sys().K) *
                                                       m.cwiseSqrt().cwiseInverse().asDiagonal());
  const Vector u0 = 1e-3 * m.cwiseSqrt().cwiseInverse().asDiagonal() *
                    (eig.eigenvectors().col(0) + 0.5 * eig.eigenvectors().col(eig.eigenvalues().size() / 8) +
                     0.25 * eig.eigenvectors().col(eig.eigenvalues().size() / 4));
  const double w_max = std::sqrt(eig.eigenvalues().maxCoeff());
  const model::State start{0, u0 / u0.norm() * 1e-3, Vector::Zero(u0.size())};
  const double dt = std::pow(2.0, std::floor(std::log2(0.25 / w_max)));  // 4 dt <= 1 / w_max
  const double T = 1024 * dt;                                            // on every grid
  const Vector exact = model::ModalReference(c.sys(), start).displacement(T);
  std::printf("w_max = %.0f rad/s, dt = %.2e s, T = %.3f s\n", w_max, dt, T);
  for (const char* method : methods) {
    const double order = observed_order(method, c.sys(), start, exact, T, {4 * dt, 2 * dt, dt});
    EXPECT_NEAR(order, integrator_order(method), 0.3) << method;
  }
}

TEST(Arkode, ExplicitMethodPastItsStabilityLimitStopsNamingMethodTimeAndStep) {
  const Cantilever c(1e-3, 0.0);
  auto erk = make_integrator("arkode-erk2", 0.01);  // far above 2 / w_max
  model::State s = c.rest();
  erk->reset(c.sys(), s);
  try {
    erk->advance_to(50.0, s);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("arkode-erk2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = "), std::string::npos) << msg;
    EXPECT_NE(msg.find("step "), std::string::npos) << msg;
  }
}

TEST(Arkode, LibraryFailureStopsNamingMethodTimeStepAndTheFlag) {
  // A tolerance far below the unit roundoff: the error test fails at every step size down to hmin.
  const Cantilever c(1e-3, 0.25);
  auto method = make_integrator("arkode-erk5", StepControl{.dt = 1e-4, .adaptive = true, .rtol = 1e-30, .atol = 1e-40});
  model::State s = c.rest();
  method->reset(c.sys(), s);
  try {
    method->advance_to(0.5, s);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("arkode-erk5: failed at t = "), std::string::npos) << msg;
    EXPECT_NE(msg.find("(step "), std::string::npos) << msg;
    EXPECT_NE(msg.find("ARK_ERR_FAILURE (ARKODE: At t = "), std::string::npos) << msg;
  }
}

TEST(Arkode, AdaptiveModeMeetsItsToleranceAgainstTheModalSolution) {
  const Cantilever c(1e-3, 0.25);
  const Vector exact = model::ModalReference(c.sys(), c.rest()).displacement(0.5);
  for (const char* name : {"arkode-esdirk4", "arkode-sdirk2", "arkode-erk5"}) {
    auto method = make_integrator(name, StepControl{.dt = 1e-4, .adaptive = true, .rtol = 1e-6, .atol = 1e-10});
    const double err = (run(*method, c.sys(), c.rest(), 0.5) - exact).norm() / exact.norm();
    std::printf("%s adaptive rtol 1e-6: relative error %.2e in %ld steps\n", name, err, method->stats().steps);
    EXPECT_LT(err, 1e-4) << name;
  }
}

}  // namespace
}  // namespace roifem::integrators
