// roi-size against answers known without it: a budget the purely static answer (a 1-node ROI)
// already meets gives 1 node; a budget only the exact model meets gives every free node (an ROI of
// all nodes is the full model, error 0).
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

TEST(RoiSize, ALooseBudgetNeedsOneNodeAndAnExactOneEveryNode) {
  const test::TempDir dir;
  RoiSizeOptions o;
  o.scenario = short_paper_scenario(dir);
  o.timing_steps = 5;
  o.reductions = {{}};
  std::ostringstream log;
  o.max_error_mm = 100;  // far above any dynamic deviation
  const auto loose = run_roi_size(o, log);
  ASSERT_EQ(loose.rows.size(), 1u);
  EXPECT_TRUE(loose.rows[0].found);
  EXPECT_EQ(loose.rows[0].nodes, 1);
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
    return result.rows.at(0).peak_max_mm;
  };
  const double base = peak_at_306("paper-setup1.toml"), paper_scale = peak_at_306("paper-setup1-paper-errors.toml");
  std::printf("setup 1, plain condensation, 0.5 s ramp: peak max error %.4f mm, at the paper's scale %.3f mm\n", base,
              paper_scale);
  EXPECT_NEAR(paper_scale / base, 0.2515 / 0.01601, 1e-9 * paper_scale / base);
  EXPECT_NEAR(paper_scale, 6.0, 0.1);
}

TEST(RoiSize, ScenarioWithoutATargetOrABadBudgetIsAnInputError) {
  const test::TempDir dir;
  RoiSizeOptions o;
  o.scenario = short_paper_scenario(dir);
  o.max_error_mm = -1;
  std::ostringstream log;
  EXPECT_THROW(run_roi_size(o, log), InputError);
  EXPECT_THROW(condensation::parse_reduction("craig-bampton-x"), InputError);
  EXPECT_EQ(condensation::parse_reduction("craig-bampton-12").modes, 12);
}

}  // namespace
}  // namespace roifem::experiments
