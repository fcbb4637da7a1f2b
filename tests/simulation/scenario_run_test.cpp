// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/errors.hpp"
#include "h5_read.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

using test::read_h5;

scenario::Scenario paper_scenario(const std::string& roi_block, long steps, const std::string& element = "tet4") {
  const std::string text = "mesh = \"" + std::string(ROIFEM_MESH_DIR) + "/brain-800.msh\"\nelement = \"" + element + "\"\n" +
                           R"([material]
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

}  // namespace
}  // namespace roifem::simulation
