#include "integrators/trapezoid.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "common/errors.hpp"
#include "mesh/box_mesh.hpp"
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
  model::State s{0.0, Vector::Zero(c.sys().size()), Vector::Zero(c.sys().size())};
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
  model::State s{0.0, Vector::Zero(c.sys().size()), Vector::Zero(c.sys().size())};
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
  std::printf("damped, loaded: max |E + D - W - E0| / W = %.3e (W = %.3e J, D = %.3e J)\n", worst,
              ledger.external_work(), ledger.dissipated());
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
  std::printf("lowest w = %.3f %.3f %.3f rad/s\n", std::sqrt(modes.eig.eigenvalues()[0]),
              std::sqrt(modes.eig.eigenvalues()[1]), std::sqrt(modes.eig.eigenvalues()[2]));
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
  model::State s{0.0, Vector::Zero(c.sys().size()), Vector::Zero(c.sys().size())};
  Trapezoid trapezoid(0.05);
  trapezoid.reset(c.sys(), s);
  EXPECT_THROW(trapezoid.advance_to(0.07, s), InputError);
}

}  // namespace
}  // namespace roifem::integrators
