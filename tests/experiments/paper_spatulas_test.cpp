// SPDX-License-Identifier: GPL-3.0-or-later
// The paper's experiment driven by spatulas (roifem paper --drive spatulas): the spatulas' force
// at rest against an independent Lagrange-multiplier solve, and the force the surgeon feels,
// condensed against full.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "experiments/paper_experiment.hpp"
#include "test_models.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

double peak(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

class PaperSpatulas : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new test::TempDir;
    PaperOptions o;
    o.mesh = std::string(ROIFEM_MESH_DIR) + "/brain-800.msh";
    o.out = dir->path();
    o.plots = false;
    o.drive = PaperDrive::spatulas;
    o.timing_steps = 50;
    o.reductions = {condensation::parse_reduction("static"), condensation::parse_reduction("craig-bampton-200")};
    std::ostringstream log;
    results = new PaperResults(run_paper_experiment(o, log));
  }
  static void TearDownTestSuite() {
    delete results;
    delete dir;
  }
  static test::TempDir* dir;
  static PaperResults* results;
  static const PaperCurve& curve(const std::string& setup, const std::string& reduction, double ramp) {
    return *std::find_if(results->reduction_curves.begin(), results->reduction_curves.end(),
                         [&](const PaperCurve& c) { return c.setup == setup && c.reduction == reduction && c.ramp_s == ramp; });
  }
};
test::TempDir* PaperSpatulas::dir = nullptr;
PaperResults* PaperSpatulas::results = nullptr;

TEST_F(PaperSpatulas, TheForceAtRestEqualsALagrangeMultiplierSolveOfTheToolFreeModel) {
  // Second method: the tool-free model (base held), the walls' nodes moved 2 mm outwards by
  // constraints S u = G in a saddle-point system [K S^T; S 0]; the force on the tissue is K u at
  // the walls' dofs, -lambda, summed per wall.
  const test::PaperBrain brain;
  const fem::DofMap& dofs = brain.dofs();
  std::vector<Eigen::Triplet<double>> entries;
  for (Index j = 0; j < brain.model.system.K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(brain.model.system.K, j); it; ++it) entries.emplace_back(it.row(), it.col(), it.value());
  const Index n = dofs.num_free();
  Index rows = n;
  Vector rhs = Vector::Zero(n + 3 * 27);
  std::vector<std::pair<Index, int>> wall_of_row;  // (constraint row, wall)
  for (int wall = 0; wall < 2; ++wall) {
    const auto& nodes = brain.mesh.set(wall == 0 ? "opening_left" : "opening_right").nodes;
    for (int node : nodes)
      for (int c = 0; c < 3; ++c) {
        const Index dof = dofs.free_dof(node, c);
        ASSERT_GE(dof, 0);
        entries.emplace_back(rows, dof, 1.0);
        entries.emplace_back(dof, rows, 1.0);
        rhs[rows] = c == 0 ? (wall == 0 ? -2e-3 : 2e-3) : 0.0;
        wall_of_row.emplace_back(rows, wall);
        ++rows;
      }
  }
  ASSERT_EQ(rows, n + 3 * 27);
  SparseMatrix kkt(rows, rows);
  kkt.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<SparseMatrix> lu(kkt);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Vector x = lu.solve(rhs);
  Vec3 force[2] = {Vec3::Zero(), Vec3::Zero()};
  for (const auto& [row, wall] : wall_of_row) force[wall][(row - n) % 3] -= x[row];
  const double expected = std::max(force[0].norm(), force[1].norm());
  EXPECT_NEAR(results->force_N, expected, 1e-9 * expected);
  EXPECT_GT(force[1].x(), 1.0);  // about 1.45 N outwards on the right wall
}

TEST_F(PaperSpatulas, TheDampedFullModelSettlesAtTheForceAtRest) {
  for (const auto& c : results->curves)
    EXPECT_NEAR(c.force_full_mN.back(), results->force_N * 1e3, 2e-3 * results->force_N * 1e3) << c.setup << " " << c.ramp_s;
}

TEST_F(PaperSpatulas, TheFasterTheRampTheLargerTheForceErrorYetBelowThreePercent) {
  for (const std::string setup : {"setup1", "setup2"}) {
    const PaperCurve &fast = curve(setup, "static", 0.5), &middle = curve(setup, "static", 1.0),
                     &slow = curve(setup, "static", 2.0);
    EXPECT_GT(peak(fast.force_err_mN), peak(middle.force_err_mN)) << setup;
    EXPECT_GT(peak(middle.force_err_mN), peak(slow.force_err_mN)) << setup;
    EXPECT_GT(peak(slow.force_err_mN), 1.0) << setup;  // mN: condensation drops the static part's inertia
    EXPECT_LT(peak(fast.force_err_mN), 0.03 * peak(fast.force_full_mN)) << setup;
    EXPECT_LT(fast.force_err_mN.back(), 0.2 * peak(fast.force_err_mN)) << setup;  // the transient decays
  }
}

TEST_F(PaperSpatulas, TwoHundredCraigBamptonModesLowerTheForceErrorFivefold) {
  for (const std::string setup : {"setup1", "setup2"})
    EXPECT_LT(peak(curve(setup, "craig-bampton-200", 0.5).force_err_mN), 0.2 * peak(curve(setup, "static", 0.5).force_err_mN))
        << setup;
}

TEST_F(PaperSpatulas, TheWallsLeaveTheUnknownsAndTheForceErrorsAreWritten) {
  EXPECT_EQ(results->timing[1].nodes, 306 - 27);  // the same ROI as the forces' setup, less the walls
  EXPECT_EQ(results->timing[2].nodes, 228 - 27);
  std::ifstream csv(dir->path() / "force_errors.csv");
  std::string header;
  std::getline(csv, header);  // "# roifem VERSION"
  std::getline(csv, header);
  EXPECT_EQ(header, "setup,reduction,ramp_s,step,time_s,force_full_mN,force_err_mN");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 2 * 2 * 3 * 200);
}

}  // namespace
}  // namespace roifem::experiments
