// The accuracy study's tools: Richardson extrapolation on analytic sequences, the point locator on
// fields it must read exactly, and the CalculiX deck against roifem's own small-strain answer.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "experiments/calculix_static.hpp"
#include "experiments/model_error.hpp"
#include "experiments/richardson.hpp"
#include "fem/loads.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/point_locator.hpp"

namespace roifem::experiments {
namespace {

TEST(Richardson, RecoversOrderAndLimitOfAPowerLawOnUnevenMeshes) {
  // q(h) = 3 + 0.7 h^1.6 on meshes whose ratios differ (1.7 and 2.3).
  const std::vector<double> h{10.0, 10.0 / 1.7, 10.0 / 1.7 / 2.3};
  std::vector<double> q;
  for (double x : h) q.push_back(3 + 0.7 * std::pow(x, 1.6));
  const auto e = richardson(h, q, 2.0);
  EXPECT_TRUE(e.observed);
  EXPECT_NEAR(e.order, 1.6, 1e-9);
  EXPECT_NEAR(e.value, 3.0, 1e-9);
}

TEST(Richardson, FallsBackToTheFormalOrderWhenTheDifferencesChangeSign) {
  const std::vector<double> h{4, 2, 1}, q{1.0, 1.2, 1.1};
  EXPECT_FALSE(observed_order(h[0], h[1], h[2], q[0], q[1], q[2]));
  const auto e = richardson(h, q, 2.0);
  EXPECT_FALSE(e.observed);
  EXPECT_DOUBLE_EQ(e.order, 2.0);
  EXPECT_NEAR(e.value, 1.1 + (1.1 - 1.2) / 3, 1e-15);  // (h2/h3)^2 - 1 = 3
  EXPECT_THROW(richardson(std::vector<double>{1, 2}, std::vector<double>{1, 2}, 2.0), InputError);
}

TEST(PointLocator, ReadsALinearFieldExactlyInsideAndTheNearestBoundaryPointOutside) {
  const mesh::TetMesh m = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  Vector u(3 * m.num_nodes());
  auto field = [](const Vec3& x) { return Vec3(2 * x.x() - x.z(), 0.5 * x.y() + 1, x.x() + x.y() + x.z()); };
  for (Index n = 0; n < m.num_nodes(); ++n) u.segment<3>(3 * n) = field(m.node(static_cast<int>(n)));
  const mesh::PointLocator locator(m);
  for (const Vec3& p : {Vec3(0.01, -0.02, 0.0), Vec3(-0.03, 0.04, -0.01), Vec3(0.0, 0.0, 0.029)}) {
    const auto at = locator.locate(p);
    EXPECT_EQ(at.outside_distance, 0);
    EXPECT_LT((mesh::PointLocator::interpolate(at, u) - field(p)).norm(), 1e-12);
  }
  // A node reads its own value; the centre of the opening (in the slit, 2 mm from each wall)
  // reads the right wall, x = +2 mm.
  EXPECT_LT((mesh::PointLocator::interpolate(locator.locate(m.node(17)), u) - u.segment<3>(51)).norm(), 1e-12);
  const auto slit = locator.locate(Vec3(0, 0, 0.04));
  EXPECT_NEAR(slit.outside_distance, 0.002, 1e-9);
  EXPECT_LT((mesh::PointLocator::interpolate(slit, u) - field(Vec3(0.002, 0, 0.04))).norm(), 1e-12);
}

class CalculixDeck : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  }
};

TEST_F(CalculixDeck, SmallStrainAnswerEqualsRoifemsAndTheNonlinearOneTendsToItAsTheLoadVanishes) {
  const mesh::TetMesh m = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const std::vector<model::SetLoad> loads{{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0}, std::nullopt},
                                          {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0}, std::nullopt}};
  const auto dir = std::filesystem::path(::testing::TempDir()) / "roifem_calculix";
  std::ostringstream log;
  // The nonlinear difference is of the order of the strain: halving the load halves it.
  const auto study = measure_model_error(m, fem::material_preset("paper"), {"base"}, loads, {0.01, 0.02, 0.04}, dir, log);
  EXPECT_LT(study.linear_check, 1e-6);
  ASSERT_EQ(study.rows.size(), 3u);
  for (std::size_t i = 1; i < 3; ++i) EXPECT_NEAR(study.rows[i].relative() / study.rows[i - 1].relative(), 2.0, 0.15);
  EXPECT_LT(study.rows[0].relative(), 0.02);
  EXPECT_GT(study.rows[0].relative(), 1e-4);  // geometric nonlinearity is there
  EXPECT_NEAR(study.rows[0].opening_linear_mm / study.rows[0].opening_nonlinear_mm, 1.0, 0.01);
  EXPECT_FALSE(study.within_10_percent_up_to_mm);
}

}  // namespace
}  // namespace roifem::experiments
