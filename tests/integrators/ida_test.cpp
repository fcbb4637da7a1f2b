// SPDX-License-Identifier: GPL-3.0-or-later
// IDA (ida.hpp, ida_roi_dae.hpp): BDF on the second-order system against the modal solution, and
// the uncondensed ROI DAE (static part algebraic) against the condensed model.
#include "integrators/ida.hpp"

#include <gtest/gtest.h>

#include "condensation/reduced_model.hpp"
#include "integrators/factory.hpp"
#include "integrators/ida_roi_dae.hpp"
#include "integrators/test_problems.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/modal_reference.hpp"

namespace roifem::integrators {
namespace {

using test_problems::Cantilever;
using test_problems::run;

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
      EXPECT_LT(err, previous);                                // tighter tolerance, smaller error
      previous = err;
    }
  }
}

TEST(IdaRoiDae, TrajectoryEqualsTheCondensedModelToTheTolerance) {
  // The paper's brain, setup 2's ROI: the DAE keeps u_s as algebraic unknowns, the condensed
  // model eliminates it; both must give the same ROI motion (exact: the modal solution of the
  // condensed model) and the same static part.
  const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const auto model = model::build_fem_model(
      mesh, fem::material_preset("paper"), {"base"},
      {{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0.5}}, {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0.5}}});
  const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.040), .radius = 0, .count = 228, .set = {}};
  const auto partition = roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  condensation::ReducedModel condensed(model.system, partition, *model.dofs);
  const model::ModalReference exact(condensed.system(), model::State::at_rest(condensed.system().size()));

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
  std::printf("IDA DAE vs exact condensed: ROI %.2e, static part %.2e (relative), %ld steps\n", worst_d, worst_s, st.steps);
  EXPECT_LT(worst_d, 1e-5);
  EXPECT_LT(worst_s, 1e-5);
}

}  // namespace
}  // namespace roifem::integrators

namespace roifem::integrators {
namespace {

// A solution that presses on an inversion: y' = 1, with every other residual beyond y = 0.5
// refused as a model refuses an inverted element (recoverable: IDA retries smaller). IDA alone
// would crawl on; the solver stops at its stated bound and names the element, the step and t.
TEST(IdaSolver, StopsAfterTheStatedNumberOfRefusedIteratesNamingTheElementStepAndTime) {
  SparseMatrix dF_dy(1, 1), dF_dyp(1, 1);
  dF_dy.insert(0, 0) = 0.0;
  dF_dyp.insert(0, 0) = 1.0;
  dF_dy.makeCompressed();
  dF_dyp.makeCompressed();
  long calls = 0, refused = 0;
  sundials::IdaSolver ida(
      {.name = "test-ida", .rtol = 1e-8, .atol = 1e-10},
      [&](double, const auto& y, const auto& yp, auto r) {
        if (y[0] > 0.5 && ++calls % 2 == 0) {
          ++refused;
          throw ModelError("tetrahedron 7 (nodes 1 2 3 4) has inverted: det F = -0.1 <= 0");
        }
        r[0] = yp[0] - 1.0;
      },
      dF_dy, dF_dyp);
  ida.y()[0] = 0;
  ida.yp()[0] = 1;
  ida.start(0);
  EXPECT_NO_THROW(ida.advance_to(0.5));
  try {
    ida.advance_to(1.0);
    FAIL() << "IDA went on past " << sundials::IdaSolver::max_refused_per_output << " refused iterates";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test-ida: step "), std::string::npos) << what;
    const std::size_t at = what.find(", t = ");
    ASSERT_NE(at, std::string::npos) << what;
    const double t = std::stod(what.substr(at + 6));
    EXPECT_GT(t, 0.5) << what;  // where the refusals began
    EXPECT_LT(t, 1.0) << what;
    EXPECT_NE(what.find("tetrahedron 7 (nodes 1 2 3 4) has inverted"), std::string::npos) << what;
  }
  EXPECT_EQ(refused, sundials::IdaSolver::max_refused_per_output);
}

}  // namespace
}  // namespace roifem::integrators
