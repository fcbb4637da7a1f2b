// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/modal_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"

namespace roifem::model {
namespace {

SecondOrderSystem single_dof(double m, double k, double alpha, double force, double ramp) {
  SecondOrderSystem s;
  s.M = diagonal_matrix(Vector::Constant(1, m));
  s.K = diagonal_matrix(Vector::Constant(1, k));
  s.C = diagonal_matrix(Vector::Constant(1, alpha * m));
  s.load = LoadHistory(1);
  if (force != 0) s.load.add(Vector::Constant(1, force), Ramp{ramp});
  return s;
}

TEST(ModalReference, FreeDampedOscillatorMatchesTheTextbookFormula) {
  const double m = 2, k = 50, alpha = 0.8, u0 = 0.01, v0 = -0.03;
  const SecondOrderSystem s = single_dof(m, k, alpha, 0, 0);
  const ModalReference ref(s, State{0, Vector::Constant(1, u0), Vector::Constant(1, v0)});
  const double w = std::sqrt(k / m), a = alpha / 2, wd = std::sqrt(w * w - a * a);
  for (double t : {0.0, 0.3, 1.7, 4.0}) {
    const double exact = std::exp(-a * t) * (u0 * std::cos(wd * t) + (v0 + a * u0) / wd * std::sin(wd * t));
    EXPECT_NEAR(ref.displacement(t)[0], exact, 1e-14) << t;
  }
}

TEST(ModalReference, OverdampedStepResponseSettlesAtTheStaticAnswer) {
  const SecondOrderSystem s = single_dof(1, 4, 10.0, 3.0, 0.0);  // w = 2 < alpha / 2 = 5
  const ModalReference ref(s, model::State::at_rest(1));
  EXPECT_NEAR(ref.displacement(0)[0], 0.0, 1e-15);
  // The slow root is -5 + sqrt(21) = -0.417 1/s: within 1e-12 of the static answer after 70 s.
  EXPECT_NEAR(ref.displacement(70)[0], 3.0 / 4.0, 1e-12);
  // Overdamped: monotone rise, no overshoot.
  double previous = 0;
  for (double t = 0.1; t < 10; t += 0.1) {
    const double u = ref.displacement(t)[0];
    EXPECT_GE(u, previous - 1e-15);
    EXPECT_LE(u, 0.75 + 1e-12);
    previous = u;
  }
}

TEST(ModalReference, RampResponseAgreesWithAFineTrapezoidalRun) {
  // A second method, independent of the closed form: the trapezoidal rule at a tiny step.
  const mesh::TetMesh mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  const FemModel model = build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                         {{"x1", Vec3(0, 0, 1e-3), Ramp{0.3}}});
  const State start = model::State::at_rest(model.system.size());
  const ModalReference ref(model.system, start);
  integrators::Trapezoid trapezoid(1e-4);
  State s = start;
  trapezoid.reset(model.system, s);
  trapezoid.advance_to(0.5, s);
  const Vector exact = ref.displacement(0.5);
  EXPECT_LT((s.u - exact).norm() / exact.norm(), 1e-4);
}

}  // namespace
}  // namespace roifem::model

namespace roifem::model {
namespace {

TEST(ModalReference, VelocityIsTheTimeDerivativeOfDisplacement) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(3, 2, 2, 0.03, 0.02, 0.02);
  const FemModel model = build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                         {{"x1", Vec3(0, 1e-3, 1e-3), Ramp{0.2}}});
  const ModalReference ref(model.system, model::State::at_rest(model.system.size()));
  for (double t : {0.05, 0.3}) {  // central differences, inside and after the ramp
    const double h = 1e-6;
    const Vector numeric = (ref.displacement(t + h) - ref.displacement(t - h)) / (2 * h);
    EXPECT_LT((ref.velocity(t) - numeric).norm(), 1e-6 * ref.velocity(t).norm()) << t;
  }
}

}  // namespace
}  // namespace roifem::model

namespace roifem::model {
namespace {

TEST(ModalReference, AnotherRampReusesTheModesAndEqualsAFreshSolution) {
  const SecondOrderSystem slow = single_dof(2.0, 50.0, 0.4, 3.0, 0.8), fast = single_dof(2.0, 50.0, 0.4, 3.0, 0.2);
  const ModalReference from_slow = ModalReference(slow, State::at_rest(1)).with_ramp(0.2);
  const ModalReference fresh(fast, State::at_rest(1));
  for (double t : {0.1, 0.2, 0.55, 2.0}) EXPECT_NEAR(from_slow.displacement(t)[0], fresh.displacement(t)[0], 1e-15) << t;
  EXPECT_GT(std::abs(from_slow.displacement(0.55)[0] - ModalReference(slow, State::at_rest(1)).displacement(0.55)[0]), 1e-3);
}

}  // namespace
}  // namespace roifem::model
