// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "h5_read.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

using test::read_h5;

scenario::Scenario paper_scenario(const std::string& roi_block, long steps, const std::string& element = "tet4",
                                  const std::string& material_model = "linear") {
  const std::string text = "mesh = \"" + std::string(ROIFEM_MESH_DIR) + "/brain-800.msh\"\nelement = \"" + element + "\"\n" +
                           "[material]\n" + (material_model == "linear" ? "" : "model = \"" + material_model + "\"\n") + R"(
preset = "paper"
[[load]]
set = "opening_left"
force_N = [-0.02, 0, 0]
ramp_s = 0.5
[[load]]
set = "opening_right"
force_N = [0.02, 0, 0]
ramp_s = 0.5
)" + roi_block +
                           "[time]\ndt_s = 0.05\nsteps = " + std::to_string(steps) + "\n[output]\nfield_every = 10\n";
  return scenario::parse_scenario(text, "test.toml", ".");
}

TEST(ScenarioRun, RoiOfAllNodesWritesTheSameFieldsAsTheFullModel) {
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(paper_scenario("", 40), dir / "full", log);
  run_scenario(paper_scenario("[roi]\nkind = \"all\"\n", 40), dir / "all", log);
  const auto a = read_h5(dir / "full/results.h5", "/fields/displacement_mm_000040");
  const auto b = read_h5(dir / "all/results.h5", "/fields/displacement_mm_000040");
  ASSERT_EQ(a.size(), b.size());
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    norm = std::max(norm, std::abs(a[i]));
  }
  EXPECT_GT(norm, 0.1);  // millimetres: the walls did move
  EXPECT_LT(diff, 1e-12 * norm);
}

class ScenarioRunByElement : public ::testing::TestWithParam<const char*> {};

TEST_P(ScenarioRunByElement, XdmfPointsAtDatasetsThatExistWithTheRightShape) {
  test::TempDir dir;
  std::ostringstream log;
  const std::string element = GetParam();
  run_scenario(paper_scenario("[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 100\n", 30, element), dir.path(), log);
  std::ifstream xdmf(dir / "results.xdmf");
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  const hid_t file = H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  int references = 0;
  for (std::size_t at = text.find("results.h5:"); at != std::string::npos; at = text.find("results.h5:", at + 1)) {
    const std::size_t begin = at + 11, end = text.find('<', begin);
    const std::string path = text.substr(begin, end - begin);
    // The DataItem's Dimensions attribute precedes the reference: "N 3" or "E 4".
    const std::size_t dims_at = text.rfind("Dimensions=\"", at) + 12;
    const std::string dims = text.substr(dims_at, text.find('"', dims_at) - dims_at);
    ASSERT_GT(H5Lexists(file, path.c_str(), H5P_DEFAULT), 0) << path;
    const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    hsize_t shape[2] = {0, 0};
    H5Sget_simple_extent_dims(space, shape, nullptr);
    EXPECT_EQ(std::to_string(shape[0]) + " " + std::to_string(shape[1]), dims) << path;
    H5Sclose(space);
    H5Dclose(set);
    ++references;
  }
  H5Fclose(file);
  EXPECT_EQ(references, 4 * 3);  // fields at steps 0, 10, 20, 30: topology, geometry, displacement each
  // Quadratic elements as ParaView's quadratic cells, with every node's displacement.
  EXPECT_EQ(text.find("TopologyType=\"Tetrahedron_10\"") != std::string::npos, element == "tet10");
}

INSTANTIATE_TEST_SUITE_P(ScenarioRun, ScenarioRunByElement, ::testing::Values("tet4", "tet10"));

TEST(ScenarioRun, StoredEnergiesSatisfyTheDiscreteBalance) {
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(paper_scenario("[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 306\n", 60), dir.path(), log);
  const auto K = read_h5(dir / "results.h5", "/energy/kinetic_J");
  const auto U = read_h5(dir / "results.h5", "/energy/strain_J");
  const auto D = read_h5(dir / "results.h5", "/energy/dissipated_J");
  const auto W = read_h5(dir / "results.h5", "/energy/external_work_J");
  ASSERT_EQ(K.size(), 61u);
  for (std::size_t k = 0; k < K.size(); ++k) EXPECT_NEAR(K[k] + U[k] + D[k] - W[k], 0.0, 1e-8 * W.back()) << k;
  const auto roi = read_h5(dir / "results.h5", "/roi/displacement_mm");
  EXPECT_EQ(roi.size(), 61u * 306u * 3u);
  EXPECT_EQ(read_h5(dir / "results.h5", "/time_s").back(), 60 * 0.05);
}

TEST(ScenarioRun, FailedRunLeavesAnExistingResultUntouched) {
  test::TempDir dir;
  test::write_file(dir / "results.h5", "a good result from an earlier run");
  scenario::Scenario s = paper_scenario("", 10);
  s.loads[0].set = "no_such_set";
  std::ostringstream log;
  EXPECT_THROW(run_scenario(s, dir.path(), log), InputError);
  s = paper_scenario("", 10);
  s.integrator = "euler";
  try {
    run_scenario(s, dir.path(), log);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("integrator 'euler' is unknown (valid: trapezoid"), std::string::npos) << e.what();
  }
  std::ifstream in(dir / "results.h5");
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "a good result from an earlier run");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(ScenarioRun, ANeoHookeanBrainRunsByNewtonAndKeepsItsEnergyLedger) {
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(paper_scenario("", 20, "tet4", "neo-hookean"), dir / "neo", log);
  run_scenario(paper_scenario("", 20), dir / "linear", log);
  const auto K = read_h5(dir / "neo" / "results.h5", "/energy/kinetic_J");
  const auto U = read_h5(dir / "neo" / "results.h5", "/energy/strain_J");
  const auto D = read_h5(dir / "neo" / "results.h5", "/energy/dissipated_J");
  const auto W = read_h5(dir / "neo" / "results.h5", "/energy/external_work_J");
  ASSERT_EQ(K.size(), 21u);
  // The trapezoidal rule's balance is exact only for a linear system: here within its O(dt^2) error.
  for (std::size_t k = 0; k < K.size(); ++k) EXPECT_NEAR(K[k] + U[k] + D[k] - W[k], 0.0, 1e-2 * W.back()) << k;
  const auto u_neo = read_h5(dir / "neo" / "results.h5", "/fields/displacement_mm_000020");
  const auto u_lin = read_h5(dir / "linear" / "results.h5", "/fields/displacement_mm_000020");
  ASSERT_EQ(u_neo.size(), u_lin.size());
  double difference = 0, peak = 0;
  for (std::size_t i = 0; i < u_neo.size(); ++i) {
    difference = std::max(difference, std::abs(u_neo[i] - u_lin[i]));
    peak = std::max(peak, std::abs(u_lin[i]));
  }
  std::printf("paper brain, 20 mN per wall, 20 steps: max |u_neo-hookean - u_linear| = %.3f mm of a %.3f mm peak\n%s", difference,
              peak, log.str().c_str());
  EXPECT_GT(difference, 1e-3 * peak) << "the two laws differ";
  EXPECT_LT(difference, 0.5 * peak);
  EXPECT_NE(log.str().find("Newton"), std::string::npos) << log.str();
}

TEST(ScenarioRun, ANeoHookeanModelRefusesWhatIsNotBuiltForItByName) {
  test::TempDir dir;
  test::write_file(dir / "results.h5", "a good result from an earlier run");
  std::ostringstream log;
  auto message = [&](const scenario::Scenario& s) {
    try {
      run_scenario(s, dir.path(), log);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  const std::string guyan = message(paper_scenario(
      "[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 100\nreduction = \"guyan\"\n", 5, "tet4", "neo-hookean"));
  EXPECT_NE(guyan.find("test.toml: [roi] reduction = \"guyan\" with a neo-hookean material"), std::string::npos) << guyan;
  scenario::Scenario implicit = paper_scenario("", 5, "tet4", "neo-hookean");
  implicit.integrator = "arkode-sdirk2-schur";
  const std::string method = message(implicit);
  EXPECT_NE(method.find("arkode-sdirk2-schur does not take a nonlinear model (neo-hookean, every element)"), std::string::npos)
      << method;
  const std::string element = message(
      paper_scenario("[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 100\n", 5, "nodal-pressure", "neo-hookean"));
  EXPECT_NE(element.find("the hybrid ROI does not take the nodal-pressure element at finite strain"), std::string::npos)
      << element;
  std::ifstream in(dir / "results.h5");
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "a good result from an earlier run");
}

/// max over `nodes` (all when empty) of |a - b| between two (N, 3) fields.
double max_distance(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& nodes = {}) {
  double worst = 0;
  const std::size_t count = nodes.empty() ? a.size() / 3 : nodes.size();
  for (std::size_t k = 0; k < count; ++k) {
    const auto n = nodes.empty() ? k : static_cast<std::size_t>(nodes[k]);
    worst = std::max(worst, std::hypot(a[3 * n] - b[3 * n], a[3 * n + 1] - b[3 * n + 1], a[3 * n + 2] - b[3 * n + 2]));
  }
  return worst;
}

TEST(ScenarioRun, AHybridRoiOfEveryFreeNodeIsTheFullNonlinearModel) {
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(paper_scenario("", 10, "tet4", "neo-hookean"), dir / "full", log);
  run_scenario(paper_scenario("[roi]\nkind = \"all\"\n", 10, "tet4", "neo-hookean"), dir / "all", log);
  const auto full = read_h5(dir / "full" / "results.h5", "/fields/displacement_mm_000010");
  const auto all = read_h5(dir / "all" / "results.h5", "/fields/displacement_mm_000010");
  const double peak = max_distance(full, std::vector<double>(full.size(), 0.0));
  std::printf("hybrid ROI of every free node against the full neo-Hookean model: %.2e of a %.3f mm peak\n",
              max_distance(full, all) / peak, peak);
  EXPECT_LT(max_distance(full, all), 1e-9 * peak);
}

/// The paper's spatulas (the walls held and moved `mm` apart each over 0.5 s) on the shipped brain.
scenario::Scenario spatula_scenario(const std::string& roi_block, long steps, double mm, const std::string& material_model) {
  const std::string text = "mesh = \"" + std::string(ROIFEM_MESH_DIR) +
                           "/brain-800.msh\"\n[material]\npreset = \"paper\"\nmodel = \"" + material_model + "\"\n" +
                           format(R"([[tool]]
name = "left"
set = "opening_left"
displacement_mm = [%g, 0, 0]
ramp_s = 0.5
[[tool]]
name = "right"
set = "opening_right"
displacement_mm = [%g, 0, 0]
ramp_s = 0.5
)",
                                  -mm, mm) +
                           roi_block + "[time]\ndt_s = 0.05\nsteps = " + std::to_string(steps) + "\n[output]\nfield_every = 10\n";
  return scenario::parse_scenario(text, "test.toml", ".");
}

TEST(ScenarioRun, AHybridRoiOfEveryFreeNodeWithSpatulasIsTheFullNonlinearModel) {
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(spatula_scenario("", 10, 2.0, "neo-hookean"), dir / "full", log);
  run_scenario(spatula_scenario("[roi]\nkind = \"all\"\n", 10, 2.0, "neo-hookean"), dir / "all", log);
  run_scenario(spatula_scenario("", 10, 2.0, "linear"), dir / "linear", log);
  const auto full = read_h5(dir / "full" / "results.h5", "/fields/displacement_mm_000010");
  const auto all = read_h5(dir / "all" / "results.h5", "/fields/displacement_mm_000010");
  const auto F_full = read_h5(dir / "full" / "results.h5", "/tools/left/force_N");
  const auto F_all = read_h5(dir / "all" / "results.h5", "/tools/left/force_N");
  const auto F_linear = read_h5(dir / "linear" / "results.h5", "/tools/left/force_N");
  ASSERT_EQ(F_full.size(), F_all.size());
  double force_gap = 0, force_peak = 0, law_gap = 0;
  for (std::size_t i = 0; i < F_full.size(); ++i) {
    force_gap = std::max(force_gap, std::abs(F_full[i] - F_all[i]));
    force_peak = std::max(force_peak, std::abs(F_full[i]));
    law_gap = std::max(law_gap, std::abs(F_full[i] - F_linear[i]));
  }
  const double peak = max_distance(full, std::vector<double>(full.size(), 0.0));
  std::printf(
      "spatulas 2 mm each, hybrid ROI of every free node against the full neo-Hookean model: fields %.2e of a %.3f mm "
      "peak, the left spatula's force %.2e of %.4f N (the linear law's differs by %.4f N)\n",
      max_distance(full, all) / peak, peak, force_gap / force_peak, force_peak, law_gap);
  EXPECT_LT(max_distance(full, all), 1e-9 * peak);
  EXPECT_LT(force_gap, 1e-9 * force_peak);
  EXPECT_GT(law_gap, 1e-3 * force_peak) << "the law changes the spatula's force";
}

TEST(ScenarioRun, TheHybridRoiIsCloserToTheFullNonlinearModelThanTheLinearCondensation) {
  // The paper's setup 1 (306 ROI nodes around the opening) at 20 mN per wall, against the full
  // neo-Hookean model: the hybrid's error against the linear condensed model's and the full linear model's.
  test::TempDir dir;
  std::ostringstream log;
  const std::string setup1 = "[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 306\n";
  run_scenario(paper_scenario("", 20, "tet4", "neo-hookean"), dir / "reference", log);
  run_scenario(paper_scenario(setup1, 20, "tet4", "neo-hookean"), dir / "hybrid", log);
  run_scenario(paper_scenario(setup1, 20), dir / "condensed", log);
  run_scenario(paper_scenario("", 20), dir / "linear", log);
  const auto roi = read_h5(dir / "hybrid" / "results.h5", "/roi/nodes");
  ASSERT_EQ(roi.size(), 306u);
  std::printf(
      "setup 1, 20 mN per wall: max error over the ROI against the full neo-Hookean model (mm)\n"
      "  step   hybrid   linear condensed   full linear   (reference peak)\n");
  double hybrid_worst = 0, condensed_worst = 0;
  for (const char* step : {"000010", "000020"}) {
    const std::string field = std::string("/fields/displacement_mm_") + step;
    const auto reference = read_h5(dir / "reference" / "results.h5", field);
    const double hybrid = max_distance(reference, read_h5(dir / "hybrid" / "results.h5", field), roi);
    const double condensed = max_distance(reference, read_h5(dir / "condensed" / "results.h5", field), roi);
    const double linear = max_distance(reference, read_h5(dir / "linear" / "results.h5", field), roi);
    std::printf("  %s  %7.4f  %17.4f  %12.4f   (%.3f)\n", step, hybrid, condensed, linear,
                max_distance(reference, std::vector<double>(reference.size(), 0.0), roi));
    hybrid_worst = std::max(hybrid_worst, hybrid);
    condensed_worst = std::max(condensed_worst, condensed);
  }
  EXPECT_LT(hybrid_worst, 0.5 * condensed_worst);
}

}  // namespace
}  // namespace roifem::simulation
