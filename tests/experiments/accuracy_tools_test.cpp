// SPDX-License-Identifier: GPL-3.0-or-later
// The accuracy study's tools: Richardson extrapolation on analytic sequences, the point locator on
// fields it must read exactly, the CalculiX deck against roifem's own small-strain answer, and
// meshes adapted by the error estimate against uniform ones.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "experiments/calculix_static.hpp"
#include "experiments/convergence_study.hpp"
#include "experiments/model_error.hpp"
#include "experiments/richardson.hpp"
#include "fem/loads.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/point_locator.hpp"
#include "test_support.hpp"

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
  const test::TempDir scratch;  // each run its own: two test runs at once shared /tmp/roifem_calculix
  const auto dir = scratch / "calculix";
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

// With linear tetrahedra (conforming: the discrete solution minimises the potential energy over a
// subspace) the work of the opening forces is a lower bound that grows towards the exact one:
// F (opening - opening_h) = ||u - u_h||_E^2. So at the same node count, a larger opening is a
// smaller energy error, whatever the estimate says: the adapted meshes must open wider.
TEST(ConvergenceStudy, AdaptedMeshesOpenWiderThanUniformOnesAtTheSameNodeCount) {
  const test::TempDir dir;
  ConvergenceOptions o{.scenario = std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup1.toml",
                       .nodes = {400, 800},
                       .out = dir.path(),
                       .element = fem::Element::tet4,
                       .modes = 1,
                       .dynamic = false,
                       .plots = false};
  // Quadratic tetrahedra on the same meshes hold every linear field among theirs, with the same
  // supports and the same work functional: their opening can only be larger.
  o.c3d10 = calculix_available();
  std::ostringstream log;
  const ConvergenceResults uniform = run_convergence_study(o, log);
  if (o.c3d10)
    for (const auto& m : uniform.meshes) {
      std::printf("%lld nodes: tet4 %.4f mm, C3D10 (%lld dofs) %.4f mm\n", static_cast<long long>(m.nodes), m.opening_mm,
                  static_cast<long long>(m.c3d10_dofs), m.c3d10_opening_mm);
      EXPECT_GT(m.c3d10_opening_mm, m.opening_mm);
    }
  o.c3d10 = false;
  o.adapt_passes = 2;
  const ConvergenceResults adapted = run_convergence_study(o, log);
  for (std::size_t k = 0; k < o.nodes.size(); ++k) {
    const auto &u = uniform.meshes[k], &a = adapted.meshes[k];
    std::printf("%lld nodes: uniform %lld nodes, opening %.4f mm, estimated error %.1f%%; adapted %lld nodes, %.4f mm, %.1f%%\n",
                static_cast<long long>(o.nodes[k]), static_cast<long long>(u.nodes), u.opening_mm, 100 * u.estimated_error,
                static_cast<long long>(a.nodes), a.opening_mm, 100 * a.estimated_error);
    EXPECT_NEAR(static_cast<double>(a.nodes), static_cast<double>(o.nodes[k]), 0.05 * static_cast<double>(o.nodes[k]));
    EXPECT_GT(a.opening_mm, 1.1 * u.opening_mm);
    EXPECT_LT(a.estimated_error, u.estimated_error);
  }
  EXPECT_NE(log.str().find("adaptation 2: estimated energy error"), std::string::npos) << log.str();
  o.adapt_passes = 7;
  EXPECT_THROW(run_convergence_study(o, log), InputError);
}

}  // namespace
}  // namespace roifem::experiments
