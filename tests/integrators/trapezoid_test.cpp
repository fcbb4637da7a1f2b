// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/trapezoid.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "common/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/energy.hpp"
#include "model/fem_model.hpp"

namespace roifem::integrators {
namespace {

/// A small cantilever block: fixed at x = 0, pulled at x = L.
struct Cantilever {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  model::FemModel model;
  Cantilever(double alpha, double force, double ramp) {
    fem::Material m = fem::Material::from_young_poisson(3000, 0.45, 1000, alpha);
    model = model::build_fem_model(mesh, m, {"x0"}, {{"x1", Vec3(0, 0, force), model::Ramp{ramp}}});
  }
  const model::SecondOrderSystem& sys() const { return model.system; }
};

TEST(Trapezoid, ConservesDiscreteEnergyWithoutDampingOrLoad) {
  const Cantilever c(0.0, 0.0, 0.0);
  model::State s = model::State::at_rest(c.sys().size());
  for (Index i = 0; i < s.u.size(); ++i) s.u[i] = 1e-4 * std::sin(0.37 * static_cast<double>(i));  // rough start
  Trapezoid trapezoid(0.01);
  trapezoid.reset(c.sys(), s);
  model::EnergyLedger ledger(c.sys(), s);
  const double E0 = ledger.total();
  double worst = 0;
  for (int k = 0; k < 1000; ++k) {
    trapezoid.step(s);
    ledger.record(s);
    worst = std::max(worst, std::abs(ledger.total() - E0) / E0);
  }
  std::printf("undamped, unloaded: max |E - E0| / E0 over 1000 steps = %.3e\n", worst);
  EXPECT_LT(worst, 1e-10);
}

TEST(Trapezoid, EnergyBalanceHoldsWithDampingAndLoad) {
  const Cantilever c(0.8, 0.05, 0.3);
  model::State s = model::State::at_rest(c.sys().size());
  Trapezoid trapezoid(0.01);
  trapezoid.reset(c.sys(), s);
  model::EnergyLedger ledger(c.sys(), s);
  double worst = 0;
  for (int k = 0; k < 500; ++k) {
    trapezoid.step(s);
    ledger.record(s);
    worst = std::max(worst, std::abs(ledger.balance_residual()) / ledger.external_work());
  }
  EXPECT_GT(ledger.dissipated(), 0.01 * ledger.external_work());  // damping did real work
  std::printf("damped, loaded: max |E + D - W - E0| / W = %.3e (W = %.3e J, D = %.3e J)\n", worst, ledger.external_work(),
              ledger.dissipated());
  EXPECT_LT(worst, 1e-8);
}

/// Exact damped free vibration by modal superposition: with C = alpha M every mode obeys
/// q'' + alpha q' + w^2 q = 0 (M-orthonormal modes from the eigenvectors of M^-1/2 K M^-1/2).
struct Modes {
  Vector s, si;  // M^1/2, M^-1/2 (diagonal)
  Eigen::SelfAdjointEigenSolver<DenseMatrix> eig;
  explicit Modes(const model::SecondOrderSystem& sys) {
    s = DenseMatrix(sys.M).diagonal().cwiseSqrt();
    si = s.cwiseInverse();
    eig.compute(si.asDiagonal() * DenseMatrix(sys.K) * si.asDiagonal());
  }
  Vector mode(Index i) const { return si.asDiagonal() * eig.eigenvectors().col(i); }
  Vector free_vibration(double alpha, const Vector& u0, double t) const {
    const DenseMatrix& Q = eig.eigenvectors();
    const Vector q0 = Q.transpose() * (s.asDiagonal() * u0);
    Vector q(q0.size());
    for (Index i = 0; i < q.size(); ++i) {
      const double a = alpha / 2, wd = std::sqrt(eig.eigenvalues()[i] - a * a);
      q[i] = q0[i] * std::exp(-a * t) * (std::cos(wd * t) + a / wd * std::sin(wd * t));
    }
    return si.asDiagonal() * (Q * q);
  }
};

TEST(Trapezoid, IsSecondOrderAgainstTheExactModalSolution) {
  const Cantilever c(0.8, 0.0, 0.0);
  const Modes modes(c.sys());
  const Vector u0 = 1e-3 * (modes.mode(0) + 0.5 * modes.mode(1) + 0.25 * modes.mode(2)) / modes.mode(0).norm();
  std::printf("lowest w = %.3f %.3f %.3f rad/s\n", std::sqrt(modes.eig.eigenvalues()[0]), std::sqrt(modes.eig.eigenvalues()[1]),
              std::sqrt(modes.eig.eigenvalues()[2]));
  const double T = 1.0;
  const Vector exact = modes.free_vibration(0.8, u0, T);
  double previous = 0;
  for (double dt : {0.01, 0.005, 0.0025, 0.00125}) {
    model::State s{0.0, u0, Vector::Zero(u0.size())};
    Trapezoid trapezoid(dt);
    trapezoid.reset(c.sys(), s);
    trapezoid.advance_to(T, s);
    const double err = (s.u - exact).norm() / exact.norm();
    if (previous > 0) {
      const double order = std::log(previous / err) / std::log(2.0);
      std::printf("dt = %.4f  relative error %.3e  observed order %.3f\n", dt, err, order);
      EXPECT_NEAR(order, 2.0, 0.1);
    } else {
      std::printf("dt = %.4f  relative error %.3e\n", dt, err);
    }
    previous = err;
  }
}

TEST(Trapezoid, RejectsNonPositiveTimeStepAndOffGridTimes) {
  EXPECT_THROW(Trapezoid(0.0), InputError);
  EXPECT_THROW(Trapezoid(-0.1), InputError);
  const Cantilever c(0.8, 0.0, 0.0);
  model::State s = model::State::at_rest(c.sys().size());
  Trapezoid trapezoid(0.05);
  trapezoid.reset(c.sys(), s);
  EXPECT_THROW(trapezoid.advance_to(0.07, s), InputError);
}

TEST(Trapezoid, ConjugateGradientsGiveTheDirectSolvesAnswerOverThePaperRun) {
  // The paper's full model (shipped brain, nearly incompressible material, walls pulled over
  // 0.5 s), 200 steps of dt = 0.05 s by both solves of K_eff.
  const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const auto model = model::build_fem_model(
      mesh, fem::material_preset("paper"), {"base"},
      {{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0.5}}, {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0.5}}});
  const auto& sys = model.system;
  model::State direct_state = model::State::at_rest(sys.size());
  model::State cg_state = direct_state;
  Trapezoid direct(0.05), cg(0.05, solvers::CgSettings{});
  direct.reset(sys, direct_state);
  cg.reset(sys, cg_state);
  EXPECT_EQ(cg.name(), "trapezoid-cg");
  double worst = 0, peak = 0;
  for (int k = 0; k < 200; ++k) {
    direct.step(direct_state);
    cg.step(cg_state);
    peak = std::max(peak, direct_state.u.norm());
    worst = std::max(worst, (cg_state.u - direct_state.u).norm());
  }
  std::printf("trapezoid-cg against trapezoid, 200 steps: max |u_cg - u| / max |u| = %.2e, %.0f CG iterations per step\n",
              worst / peak, static_cast<double>(cg.stats().lin_iterations) / 200.0);
  EXPECT_GT(peak, 1e-4);  // the walls moved (metres)
  EXPECT_LT(worst / peak, 1e-8);
  EXPECT_EQ(cg.stats().steps, 200);
  EXPECT_GT(cg.stats().lin_iterations, 200);
}

TEST(Trapezoid, ConjugateGradientsThatRunOutNameTheStep) {
  const Cantilever c(0.8, 0.05, 0.3);
  model::State s = model::State::at_rest(c.sys().size());
  Trapezoid cg(0.01, solvers::CgSettings{.tolerance = 1e-12, .max_iterations = 2});
  cg.reset(c.sys(), s);
  try {
    cg.step(s);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("trapezoid-cg: step 1, t = 0.01 s: conjugate gradients did not converge in 2"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace roifem::integrators
