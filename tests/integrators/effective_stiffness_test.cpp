// SPDX-License-Identifier: GPL-3.0-or-later
// The trapezoidal rule's one linear solve, x = K_eff^-1 (f + M w) with K_eff = K + 2/dt C + 4/dt^2 M
// (effective_stiffness.hpp, modal_elimination.hpp): every strategy against a dense Cholesky solve of
// the same system, on a Craig-Bampton model whose modal coordinates ModalElimination eliminates.
#include "integrators/effective_stiffness.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "condensation/reduced_model.hpp"
#include "integrators/modal_elimination.hpp"
#include "mesh/box_mesh.hpp"
#include "model/average_acceleration.hpp"
#include "model/fem_model.hpp"
#include "test_models.hpp"

namespace roifem::integrators {
namespace {

/// The test beam's Craig-Bampton model with 6 modal coordinates.
struct ReducedBeam {
  test::Beam beam;
  condensation::ReducedModel reduced{beam.model.system, beam.partition(), *beam.model.dofs,
                                     condensation::parse_reduction("craig-bampton-6")};
};

/// x = (K + 2/dt C + 4/dt^2 M)^-1 (f + M w) by a dense Cholesky factor, from the matrices alone.
Vector dense_reference(const model::SecondOrderSystem& s, double dt, const Vector& f, const Vector& w) {
  const DenseMatrix K_eff = DenseMatrix(s.K) + (2.0 / dt) * DenseMatrix(s.C) + (4.0 / (dt * dt)) * DenseMatrix(s.M);
  return K_eff.llt().solve(f + DenseMatrix(s.M) * w);
}

TEST(EffectiveStiffness, EveryStrategySolvesTheSameSystemAsADenseFactor) {
  const ReducedBeam beam;
  const model::SecondOrderSystem& s = beam.reduced.system();
  ASSERT_TRUE(s.modal.has_value());
  ASSERT_EQ(s.modal->count, 6);
  ASSERT_TRUE(s.damping.is_mass_proportional());
  const double dt = 0.01;
  const model::AverageAcceleration rule(dt);
  const Vector f = Vector::LinSpaced(s.size(), -1e-3, 2e-3), w = Vector::LinSpaced(s.size(), 0.5, -0.25);
  const Vector expected = dense_reference(s, dt, f, w);

  DirectSolve direct(s, rule);
  ConjugateGradients cg(s, rule, solvers::CgSettings{});
  ModalElimination modal(s, dt);
  const std::pair<const char*, EffectiveStiffnessSolver*> strategies[] = {
      {"DirectSolve", &direct}, {"ConjugateGradients", &cg}, {"ModalElimination", &modal}};
  for (const auto& [name, strategy] : strategies) {
    Vector x = Vector::Zero(s.size());  // CG's initial guess
    strategy->solve(f, w, x);
    const double error = (x - expected).norm() / expected.norm();
    std::printf("%s: relative difference from the dense solve %.2e\n", name, error);
    EXPECT_LT(error, strategy->uses_initial_guess() ? 1e-8 : 1e-11) << name;  // CG stops at a 1e-10 residual
  }
  EXPECT_GT(cg.iterations(), 0);
}

TEST(AverageAcceleration, ConsistentAccelerationSatisfiesTheEquationOfMotion) {
  const ReducedBeam beam;
  const model::SecondOrderSystem& s = beam.beam.model.system;
  const model::State state{0.1, Vector::LinSpaced(s.size(), 0, 1e-4), Vector::LinSpaced(s.size(), 1e-3, 0)};
  const Vector a = model::AverageAcceleration::consistent_acceleration(s, state);
  const Vector residual = s.M * a + s.C * state.v + s.K * state.u - s.load.at(state.t);
  EXPECT_LT(residual.norm(), 1e-12 * (s.K * state.u).norm());
}

}  // namespace
}  // namespace roifem::integrators
