// SPDX-License-Identifier: GPL-3.0-or-later
// The paper's findings, asserted on the shipped mesh (timing is printed by `roifem paper` and
// measured in benchmarks, never asserted here).
#include "experiments/paper_experiment.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace roifem::experiments {
namespace {

double peak(const PaperCurve& c) { return *std::max_element(c.max_mm.begin(), c.max_mm.end()); }
/// Recomputed here, independently of the library's steady_mean.
double mean_after_step_100(const PaperCurve& c) {
  double sum = 0;
  for (std::size_t k = 100; k < c.mean_mm.size(); ++k) sum += c.mean_mm[k];
  return sum / static_cast<double>(c.mean_mm.size() - 100);
}

class PaperExperiment : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new test::TempDir;
    PaperOptions o;
    o.mesh = std::string(ROIFEM_MESH_DIR) + "/brain-800.msh";
    o.out = dir->path();
    o.plots = false;
    o.timing_steps = 50;     // (timing is not asserted here)
    o.error_budget = false;  // (error_budget_test.cpp and the CLI test cover it)
    std::ostringstream log;
    results = new PaperResults(run_paper_experiment(o, log));
  }
  static void TearDownTestSuite() {
    delete results;
    delete dir;
  }
  static test::TempDir* dir;
  static PaperResults* results;
  static ReductionRow row(const std::string& setup, const std::string& reduction) {
    return *std::find_if(results->reductions.begin(), results->reductions.end(),
                         [&](const ReductionRow& x) { return x.setup == setup && x.reduction == reduction; });
  }
};
test::TempDir* PaperExperiment::dir = nullptr;
PaperResults* PaperExperiment::results = nullptr;

TEST_F(PaperExperiment, HasTwoSetupsTimesThreeRampsOf200Steps) {
  ASSERT_EQ(results->curves.size(), 6u);
  for (const auto& c : results->curves) EXPECT_EQ(c.mean_mm.size(), 200u);
  EXPECT_EQ(results->timing.size(), 3u);
  EXPECT_EQ(results->timing[1].nodes, 306);
  EXPECT_EQ(results->timing[2].nodes, 228);
}

TEST_F(PaperExperiment, KeepingTheStaticPartsInertiaLowersThePeakError) {
  // Guyan and Craig-Bampton carry the static part's mass, which plain condensation drops: their
  // max-error peak at the fastest ramp lies below plain condensation's on both setups.
  ASSERT_EQ(results->reductions.size(), 14u);  // 2 setups x (static, guyan, craig-bampton 5, 10, 20, 200, pod-40)
  for (const auto& row : results->reductions) {
    const auto& plain = *std::find_if(results->reductions.begin(), results->reductions.end(),
                                      [&](const ReductionRow& x) { return x.setup == row.setup && x.reduction == "static"; });
    if (row.reduction == "static") continue;
    EXPECT_LT(row.peak_max_mm, 0.7 * plain.peak_max_mm) << row.setup << " " << row.reduction;
    EXPECT_EQ(row.dofs, plain.dofs + row.extra_dofs);
  }
}

TEST_F(PaperExperiment, TwoHundredCraigBamptonModesLowerThePeakErrorTenfoldOnSetup1) {
  // The target on the paper case (ramp 0.5 s, setup 1), against the full model: a 10x
  // lower max-error peak than plain condensation with Craig-Bampton (measured 17.2x; 20 modes
  // give 2x: the error lives in many weakly driven local modes near the interface).
  EXPECT_LT(row("setup1", "craig-bampton-200").peak_max_mm, 0.1 * row("setup1", "static").peak_max_mm);
  EXPECT_LT(row("setup1", "craig-bampton-200").peak_max_mm, 0.5 * row("setup1", "craig-bampton-20").peak_max_mm);
  EXPECT_EQ(row("setup1", "craig-bampton-200").extra_dofs, 200);
}

TEST_F(PaperExperiment, FortyPodVectorsLowerThePeakErrorTenfoldOnSetup1) {
  // The same target with 40 POD vectors (measured 12.5x). The basis is learnt from step
  // responses, not from this ramp.
  EXPECT_LT(row("setup1", "pod-40").peak_max_mm, 0.1 * row("setup1", "static").peak_max_mm);
  EXPECT_LT(row("setup2", "pod-40").peak_max_mm, 0.15 * row("setup2", "static").peak_max_mm);
  EXPECT_EQ(row("setup1", "pod-40").extra_dofs, 40);
}

TEST_F(PaperExperiment, SteadyStateMeanErrorIsBelowTwoTenthsOfAMillimetre) {
  for (const auto& c : results->curves) EXPECT_LT(mean_after_step_100(c), 0.2) << c.setup << " ramp " << c.ramp_s;
}

TEST_F(PaperExperiment, FasterRampsGiveHigherMaxErrorPeaks) {
  for (int s = 0; s < 2; ++s) {
    EXPECT_GT(peak(results->curves[3 * s]), peak(results->curves[3 * s + 1]));      // 0.5 s > 1 s
    EXPECT_GT(peak(results->curves[3 * s + 1]), peak(results->curves[3 * s + 2]));  // 1 s > 2 s
  }
}

TEST_F(PaperExperiment, TheSmallerRoiPeaksHigher) {
  for (int r = 0; r < 3; ++r) EXPECT_GT(peak(results->curves[3 + r]), peak(results->curves[r])) << "ramp " << r;
}

TEST_F(PaperExperiment, ErrorsStartAtZeroAndDecayAsTheDampedTransientDies) {
  // At rest before the load and exact at the static limit: the error must shrink by the end.
  for (const auto& c : results->curves) {
    EXPECT_LT(c.max_mm.back(), 0.25 * peak(c)) << c.setup << " ramp " << c.ramp_s;
    EXPECT_LT(c.max_mm.front(), peak(c));
  }
}

TEST_F(PaperExperiment, WritesCompleteCsvAndReadableHdf5) {
  std::ifstream errors(dir->path() / "errors.csv");
  std::string header;
  std::getline(errors, header);
  EXPECT_EQ(header.rfind("# roifem ", 0), 0u) << header;
  std::getline(errors, header);
  EXPECT_EQ(header, "setup,reduction,ramp_s,step,time_s,mean_mm,max_mm");
  int rows = 0;
  for (std::string line; std::getline(errors, line);) ++rows;
  EXPECT_EQ(rows, 7 * 6 * 200);  // 7 reductions x 2 setups x 3 ramps
  std::ifstream timing(dir->path() / "timing.csv");
  std::getline(timing, header);  // "# roifem VERSION"
  std::getline(timing, header);
  EXPECT_EQ(header, "model,nodes,dofs,step_s_median,frame_rate_hz,step_s_p99,setup_s");

  const hid_t file = H5Fopen((dir->path() / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t set = H5Dopen2(file, "/errors/setup1/static/ramp_0.5s/max_mm", H5P_DEFAULT);
  ASSERT_GE(set, 0);
  std::vector<double> max_mm(200);
  EXPECT_GE(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, max_mm.data()), 0);
  EXPECT_EQ(max_mm, results->curves[0].max_mm);
  H5Dclose(set);
  H5Fclose(file);
  EXPECT_TRUE(std::filesystem::exists(dir->path() / "results.xdmf"));
  for (const auto& entry : std::filesystem::directory_iterator(dir->path()))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace roifem::experiments
