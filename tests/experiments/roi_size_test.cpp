// SPDX-License-Identifier: GPL-3.0-or-later
// roi-size against answers known without it: a budget every ROI meets gives the smallest size
// tried; a budget only the exact model meets gives every free node (an ROI of all nodes is the full
// model, error 0); for a budget in between, every size tried from the answer up holds and the one
// below misses, the peaks are those the same sizes gave in another search, and the scenario's own
// ROI errs as the same ROI found by size.
#include "experiments/roi_size.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/errors.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

/// A shipped scenario's text, its mesh path made absolute (so that a copy elsewhere reads it).
std::string shipped_scenario(const std::string& file) {
  std::ifstream in(std::string(ROIFEM_SCENARIO_DIR) + "/" + file);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s.replace(s.find("\"../meshes/brain-800.msh\""), 25, "\"" + std::string(ROIFEM_MESH_DIR) + "/brain-800.msh\"");
  return s;
}

std::filesystem::path short_paper_scenario(const test::TempDir& dir) {
  std::string s = shipped_scenario("paper-setup1.toml");
  s.replace(s.find("steps = 200"), 11, "steps = 20");
  return test::write_file(dir / "short.toml", s);
}

/// Plain condensation sized on the short paper scenario, with few timing steps.
RoiSizeOptions short_static_search(const test::TempDir& dir) {
  RoiSizeOptions o;
  o.scenario = short_paper_scenario(dir);
  o.timing_steps = 5;
  o.reductions = {{}};
  return o;
}

TEST(RoiSize, ALooseBudgetNeedsOneNodeAndAnExactOneEveryNode) {
  const test::TempDir dir;
  RoiSizeOptions o = short_static_search(dir);
  std::ostringstream log;
  o.max_error_mm = 100;  // far above any dynamic deviation
  const auto loose = run_roi_size(o, log);
  ASSERT_EQ(loose.rows.size(), 1u);
  EXPECT_TRUE(loose.rows[0].found);
  EXPECT_EQ(loose.rows[0].nodes, 1);
  EXPECT_EQ(loose.rows[0].missing_to, 0);
  o.max_error_mm = 1e-9;  // only the full model itself
  o.start_nodes = loose.free_nodes - 3;
  const auto exact = run_roi_size(o, log);
  EXPECT_EQ(exact.rows[0].nodes, exact.free_nodes);
  EXPECT_LT(exact.rows[0].peak_max_mm, 1e-9);
}

TEST(RoiSize, ThePaperErrorScaleScenarioScalesTheErrorByItsForceToThePapersSixMillimetres) {
  // The model is linear: 15.71 times the force gives 15.71 times every error, and plain
  // condensation's peak on setup 1 (0.5 s ramp) is then the paper's 6 mm.
  const test::TempDir dir;
  auto peak_at_306 = [&](const std::string& file) {
    RoiSizeOptions o;
    o.scenario = test::write_file(dir / file, shipped_scenario(file));
    o.timing_steps = 5;
    o.reductions = {{}};
    o.max_error_mm = 1e3;  // the first ROI tried holds: its peak is the answer's
    o.start_nodes = 306;
    std::ostringstream log;
    const auto result = run_roi_size(o, log);
    EXPECT_EQ(result.rows.at(0).nodes, 306);
    // The scenario's own ROI is the same 306 nodes with the same reduction: the same error.
    EXPECT_EQ(result.scenario_roi_nodes, 306);
    EXPECT_EQ(result.scenario_peak_max_mm, result.rows.at(0).peak_max_mm);
    return result.rows.at(0).peak_max_mm;
  };
  const double base = peak_at_306("paper-setup1.toml"), paper_scale = peak_at_306("paper-setup1-paper-errors.toml");
  std::printf("setup 1, plain condensation, 0.5 s ramp: peak max error %.4f mm, at the paper's scale %.3f mm\n", base,
              paper_scale);
  EXPECT_NEAR(paper_scale / base, 0.2515 / 0.01601, 1e-9 * paper_scale / base);
  EXPECT_NEAR(paper_scale, 6.0, 0.1);
}

TEST(RoiSize, EveryRoiTriedFromTheAnswerUpHoldsAndTheOneBelowMisses) {
  const test::TempDir dir;
  RoiSizeOptions o = short_static_search(dir);
  o.max_error_mm = 100;  // every size holds: the peaks of the whole coarse grid
  std::ostringstream log;
  const auto all = run_roi_size(o, log).rows.at(0).probes;
  ASSERT_GT(all.size(), 20u);
  // A budget between the peaks: the median of the sizes above 20 nodes.
  std::vector<double> peaks;
  for (const auto& p : all)
    if (p.nodes > 20 && p.peak_max_mm > 0) peaks.push_back(p.peak_max_mm);
  std::nth_element(peaks.begin(), peaks.begin() + peaks.size() / 2, peaks.end());
  o.max_error_mm = peaks[peaks.size() / 2];
  o.out = dir / "out";
  const auto row = run_roi_size(o, log).rows.at(0);
  ASSERT_TRUE(row.found);
  std::printf("budget %.4f mm: from %lld nodes (%.4f mm), misses at %lld-%lld, holds below at %lld; %zu runs\n", o.max_error_mm,
              static_cast<long long>(row.nodes), row.peak_max_mm, static_cast<long long>(row.missing_from),
              static_cast<long long>(row.missing_to), static_cast<long long>(row.holds_below), row.probes.size());
  Index below = 0;
  for (const auto& p : row.probes) {
    if (p.nodes >= row.nodes) {
      EXPECT_LE(p.peak_max_mm, o.max_error_mm) << p.nodes << " nodes";
    }
    if (p.nodes < row.nodes) below = std::max(below, p.nodes);
    // The same size in the first search: the same error.
    for (const auto& q : all)
      if (q.nodes == p.nodes) {
        EXPECT_EQ(q.peak_max_mm, p.peak_max_mm) << p.nodes << " nodes";
      }
  }
  ASSERT_GT(below, 0);
  EXPECT_EQ(below, row.missing_to);
  // The tables were written, one line per run.
  std::ifstream runs(o.out / "roi_size_runs.csv");
  std::string line;
  std::size_t lines = 0;
  while (std::getline(runs, line)) ++lines;
  EXPECT_EQ(lines, row.probes.size() + 2);  // the version line, the header, a line per run
}

TEST(RoiSize, GeometricSizesGrowByTheRatioAndEndAtTheLast) {
  EXPECT_EQ(geometric_sizes(1, 10, 0.25), (std::vector<Index>{1, 2, 3, 4, 5, 7, 9, 10}));
  EXPECT_EQ(geometric_sizes(100, 110, 0.02), (std::vector<Index>{100, 102, 105, 108, 110}));
  EXPECT_EQ(geometric_sizes(5, 5, 0.25), (std::vector<Index>{5}));
}

TEST(RoiSize, ScenarioWithoutATargetOrABadBudgetIsAnInputError) {
  const test::TempDir dir;
  RoiSizeOptions o;
  o.scenario = short_paper_scenario(dir);
  o.max_error_mm = -1;
  std::ostringstream log;
  EXPECT_THROW(run_roi_size(o, log), InputError);
  o.max_error_mm = 1;
  o.integrator = "trapezium";
  EXPECT_THROW(run_roi_size(o, log), InputError);
  EXPECT_THROW(condensation::parse_reduction("craig-bampton-x"), InputError);
  EXPECT_EQ(condensation::parse_reduction("craig-bampton-12").modes, 12);
}

}  // namespace
}  // namespace roifem::experiments
