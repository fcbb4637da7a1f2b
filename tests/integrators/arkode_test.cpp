#include "integrators/arkode.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/factory.hpp"
#include "integrators/gsl_odeiv2.hpp"
#include "integrators/ida_roi_dae.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "model/modal_reference.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::integrators {
namespace {

struct Cantilever {
  mesh::TetMesh mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  model::FemModel model;
  Cantilever(double force, double ramp) {
    model = model::build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                   {{"x1", Vec3(0, 0, force), model::Ramp{ramp}}});
  }
  const model::SecondOrderSystem& sys() const { return model.system; }
  model::State rest() const { return model::State::at_rest(sys().size()); }
};

Vector run(Integrator& integrator, const model::SecondOrderSystem& sys, model::State s, double T) {
  integrator.reset(sys, s);
  integrator.advance_to(T, s);
  return s.u;
}

TEST(Arkode, TrapezoidButcherTableEqualsTheHandWrittenRule) {
  const Cantilever c(1e-3, 0.3);
  Trapezoid hand(0.01);
  const Vector a = run(hand, c.sys(), c.rest(), 0.5);
  for (const char* name : {"arkode-trapezoid", "arkode-trapezoid-schur", "arkode-trapezoid-mass", "arkode-trapezoid-mass-schur"}) {
    auto table = make_integrator(name, 0.01);
    const Vector b = run(*table, c.sys(), c.rest(), 0.5);
    std::printf("hand-written vs %s: relative difference %.2e\n", name, (a - b).norm() / a.norm());
    EXPECT_LT((a - b).norm() / a.norm(), 1e-9) << name;
  }
}

// The same on a condensed paper model (split stiffness, dense interface block), over 200 steps
// at the paper's dt: the Schur solver's elimination and the K u cache change nothing.
TEST(Arkode, TrapezoidTableEqualsTheHandWrittenRuleOnTheCondensedPaperModel) {
  const auto model = simulation::build_scenario_model(scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup1.toml"));
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

/// Observed order between the last two step sizes, against an exact reference.
double observed_order(const std::string& method, const model::SecondOrderSystem& sys, const model::State& start,
                      const Vector& exact, double T, std::initializer_list<double> dts) {
  std::vector<double> errors;
  for (double dt : dts) {
    auto integrator = make_integrator(method, dt);
    errors.push_back((run(*integrator, sys, start, T) - exact).norm() / exact.norm());
  }
  const double order = std::log(errors[errors.size() - 2] / errors.back()) / std::log(2.0);
  std::printf("%-18s errors", method.c_str());
  for (double e : errors) std::printf(" %.2e", e);
  std::printf("  observed order %.2f (theory %d)\n", order, integrator_order(method));
  return order;
}

const char* const methods[] = {"arkode-erk2",   "arkode-erk3",    "arkode-erk4",    "arkode-erk5",     "arkode-sdirk2",
                               "arkode-ark3",   "arkode-esdirk4", "arkode-esdirk5", "arkode-trapezoid", "trapezoid"};

TEST(Arkode, EveryMethodShowsItsOrderOnADampedOscillator) {
  model::SecondOrderSystem s;
  s.M = model::diagonal_matrix(Vector::Constant(1, 1.0));
  s.K = model::diagonal_matrix(Vector::Constant(1, 25.0));  // w = 5 rad/s
  s.C = model::diagonal_matrix(Vector::Constant(1, 0.8));
  s.load = model::LoadHistory(1);
  const model::State start{0, Vector::Constant(1, 1e-3), Vector::Zero(1)};
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
  const double T = 1024 * dt;                                              // on every grid
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

}  // namespace
}  // namespace roifem::integrators

namespace roifem::integrators {
namespace {

TEST(Ida, MeetsItsToleranceAgainstTheModalSolution) {
  const Cantilever c(1e-3, 0.25);  // a ramped load
  const model::State start = c.rest();
  const Vector exact = model::ModalReference(c.sys(), start).displacement(0.5);
  for (const char* name : {"ida-bdf5", "ida-bdf2"}) {
    double previous = 1;
    for (double rtol : {1e-4, 1e-6, 1e-8}) {
      auto ida = make_integrator(name, StepControl{.dt = 1e-3, .adaptive = true, .rtol = rtol, .atol = rtol * 1e-4});
      const double err = (run(*ida, c.sys(), start, 0.5) - exact).norm() / exact.norm();
      const auto st = ida->stats();
      std::printf("%s rtol %.0e: relative error %.2e, %ld steps, %ld residuals, %ld setups\n", name, rtol, err, st.steps,
                  st.rhs_evals, st.lin_setups);
      EXPECT_LT(err, 200 * rtol) << name << " rtol " << rtol;  // global error ~ tolerance times a modest factor
      EXPECT_LT(err, previous);                                 // tighter tolerance, smaller error
      previous = err;
    }
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

namespace roifem::integrators {
namespace {

TEST(GslOdeiv2, FixedStepRungeKuttaMethodsShowTheirOrder) {
  model::SecondOrderSystem s;
  s.M = model::diagonal_matrix(Vector::Constant(1, 1.0));
  s.K = model::diagonal_matrix(Vector::Constant(1, 25.0));
  s.C = model::diagonal_matrix(Vector::Constant(1, 0.8));
  s.load = model::LoadHistory(1);
  const model::State start{0, Vector::Constant(1, 1e-3), Vector::Zero(1)};
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

}  // namespace
}  // namespace roifem::integrators

namespace roifem::integrators {
namespace {

TEST(IdaRoiDae, TrajectoryEqualsTheCondensedModelToTheTolerance) {
  // The paper's brain, setup 2's ROI: the DAE keeps u_s as algebraic unknowns, the condensed
  // model eliminates it; both must give the same ROI motion (exact: the modal solution of the
  // condensed model) and the same static part.
  const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const auto model = model::build_fem_model(
      mesh, fem::material_preset("paper"), {"base"},
      {{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0.5}}, {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0.5}}});
  const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.040), .radius = 0, .count = 228,
                          .set = {}};
  const auto partition =
      roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  condensation::ReducedModel condensed(model.system, partition, *model.dofs);
  const model::ModalReference exact(
      condensed.system(), model::State::at_rest(condensed.system().size()));

  IdaRoiDae dae(model.system, partition, StepControl{.dt = 1e-4, .adaptive = true, .rtol = 1e-8, .atol = 1e-12});
  dae.reset(0.0);
  Vector u_d, u_s;
  double worst_d = 0, worst_s = 0;
  for (double t : {0.25, 0.5, 1.0}) {
    dae.advance_to(t, u_d, u_s);
    const Vector e = exact.displacement(t);
    worst_d = std::max(worst_d, (u_d - e).norm() / e.norm());
    const Vector s = condensed.recover_static(e, t);
    worst_s = std::max(worst_s, (u_s - s).norm() / s.norm());
  }
  const auto st = dae.stats();
  std::printf("IDA DAE vs exact condensed: ROI %.2e, static part %.2e (relative), %ld steps\n", worst_d, worst_s,
              st.steps);
  EXPECT_LT(worst_d, 1e-5);
  EXPECT_LT(worst_s, 1e-5);
}

}  // namespace
}  // namespace roifem::integrators
