// SPDX-License-Identifier: GPL-3.0-or-later
// GSL odeiv2 (gsl_odeiv2.hpp): the fixed-step Runge-Kutta orders, the adaptive steppers'
// tolerances against the modal solution, and the dense-Jacobian size limit.
#include "integrators/gsl_odeiv2.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/test_problems.hpp"
#include "mesh/box_mesh.hpp"
#include "model/modal_reference.hpp"

namespace roifem::integrators {
namespace {

using test_problems::Cantilever;
using test_problems::observed_order;
using test_problems::run;

TEST(GslOdeiv2, FixedStepRungeKuttaMethodsShowTheirOrder) {
  const model::SecondOrderSystem s = test_problems::damped_oscillator();
  const model::State start = test_problems::oscillator_start();
  const Vector exact = model::ModalReference(s, start).displacement(2.0);
  for (const char* method : {"gsl-rk4", "gsl-rk4imp"}) {
    const double order = observed_order(method, s, start, exact, 2.0, {0.02, 0.01, 0.005});
    EXPECT_NEAR(order, 4.0, 0.3) << method;
  }
}

TEST(GslOdeiv2, AdaptiveSteppersMeetTheirToleranceAgainstTheModalSolution) {
  const Cantilever c(1e-3, 0.25);
  const Vector exact = model::ModalReference(c.sys(), c.rest()).displacement(0.5);
  for (const char* name : {"gsl-rk8pd", "gsl-msadams", "gsl-msbdf", "gsl-bsimp", "gsl-rk4imp"}) {
    auto method = make_integrator(name, StepControl{.dt = 1e-5, .adaptive = true, .rtol = 1e-7, .atol = 1e-12});
    const double err = (run(*method, c.sys(), c.rest(), 0.5) - exact).norm() / exact.norm();
    std::printf("%-12s adaptive rtol 1e-7: relative error %.2e in %ld steps\n", name, err, method->stats().steps);
    EXPECT_LT(err, 1e-4) << name;
  }
}

TEST(GslOdeiv2, RefusesSystemsTooLargeForDenseJacobians) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(12, 8, 8, 0.12, 0.08, 0.08);
  const auto model = model::build_fem_model(mesh, fem::material_preset("brain"), {"x0"}, {});
  ASSERT_GT(model.system.size(), max_gsl_dofs);
  auto gsl = make_integrator("gsl-msbdf", 0.01);
  try {
    gsl->reset(model.system, model::State::at_rest(model.system.size()));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dense Jacobian is limited to 2000 dofs"), std::string::npos) << e.what();
  }
}

TEST(GslOdeiv2, Rk4IsStableToTwiceClassicalRk4sLimitAsItsStepDoublingSays) {
  // An undamped oscillator, w = 5 rad/s: classical RK4 is stable up to h w = 2 sqrt(2); GSL's rk4
  // returns two half steps, so up to 4 sqrt(2) (the table's tableau says so: integrator_table_test).
  auto sys = test_problems::damped_oscillator();
  sys.C = model::diagonal_matrix(Vector::Zero(1));
  const double w = 5.0, limit = 4.0 * std::sqrt(2.0) / w;
  auto amplitude_after = [&](double dt) {
    auto rk4 = make_integrator("gsl-rk4", dt);
    model::State s = test_problems::oscillator_start();
    rk4->reset(sys, s);
    double largest = 0;
    try {
      for (int k = 1; k <= 400; ++k) {
        rk4->advance_to(dt * k, s);
        largest = std::max(largest, std::abs(s.u[0]));
      }
    } catch (const SolverError&) {
      return HUGE_VAL;  // the seam stopped the divergence
    }
    return largest / 1e-3;
  };
  EXPECT_LT(amplitude_after(0.98 * limit), 1.0 + 1e-9);                    // |R| < 1: it decays
  EXPECT_GT(amplitude_after(1.02 * limit), 10.0);                          // |R| > 1: it grows
  EXPECT_LT(amplitude_after(1.5 * 2.0 * std::sqrt(2.0) / w), 1.0 + 1e-9);  // 1.5x classical RK4's limit: still stable
}

}  // namespace
}  // namespace roifem::integrators
