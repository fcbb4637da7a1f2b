// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/reduced_model.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "test_models.hpp"

namespace roifem::condensation {
namespace {

using test::nearest;
using test::PaperBrain;

TEST(ReducedModel, CondensedStaticAnswerEqualsTheFullOneOnTheRoi) {
  const PaperBrain brain;
  const auto p = brain.partition(nearest(306));
  ASSERT_EQ(p.roi_nodes.size(), 306u);
  ASSERT_FALSE(p.interface.empty());
  ReducedModel condensed(brain.model.system, p, *brain.model.dofs);
  const double t = 1.0;  // loads fully applied
  solvers::Cholesky full, reduced;
  full.compute(brain.model.system.K);
  reduced.compute(condensed.system().K);
  const Vector u = full.solve(brain.model.system.load.at(t));
  const Vector u_d = reduced.solve(condensed.system().load.at(t));
  const Vector u_d_full = roi::gather(u, p.d);
  EXPECT_LT((u_d - u_d_full).norm() / u_d_full.norm(), 1e-10);
  // The static part recovered from the ROI equals the full answer there too.
  const Vector u_s_full = roi::gather(u, p.s);
  EXPECT_LT((condensed.recover_static(u_d, t) - u_s_full).norm() / u_s_full.norm(), 1e-10);
  std::printf("condensed vs full static: ROI %.2e, static part %.2e (relative)\n", (u_d - u_d_full).norm() / u_d_full.norm(),
              (condensed.recover_static(u_d, t) - u_s_full).norm() / u_s_full.norm());
}

TEST(ReducedModel, RoiOfAllNodesReproducesTheFullDynamicModel) {
  const PaperBrain brain;
  const auto p = brain.partition(roi::RoiSpec{});
  EXPECT_TRUE(p.s.empty());
  ReducedModel condensed(brain.model.system, p, *brain.model.dofs);
  const Index n = brain.model.system.size();
  model::State full = model::State::at_rest(n), roi = full;
  integrators::Trapezoid a(0.05), b(0.05);
  a.reset(brain.model.system, full);
  b.reset(condensed.system(), roi);
  double worst = 0;
  for (int k = 0; k < 100; ++k) {
    a.step(full);
    b.step(roi);
    worst = std::max(worst, (condensed.expand(roi.u, roi.t) - full.u).norm() / full.u.norm());
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(ReducedModel, CondensedStiffnessIsSymmetricPositiveDefinite) {
  const PaperBrain brain;
  ReducedModel condensed(brain.model.system, brain.partition(nearest(228)), *brain.model.dofs);
  const SparseMatrix& K = condensed.system().K;
  EXPECT_LT((K - SparseMatrix(K.transpose())).norm(), 1e-12 * K.norm());
  solvers::Cholesky cholesky;
  EXPECT_NO_THROW(cholesky.compute(K));
}

TEST(ReducedModel, StaticPieceHeldByNothingIsAModelErrorNamingANodeOfIt) {
  // Two boxes that share no node: the first fixed on its face x0 and holding the ROI, the second
  // held by nothing, so all static and free to move as a rigid body: K_ss is singular.
  const mesh::TetMesh a = mesh::structured_box_mesh(2, 2, 2, 0.01, 0.01, 0.01);
  mesh::TetMesh both = a;
  const Index n_a = a.num_nodes();
  both.nodes.conservativeResize(3, 2 * n_a);
  both.nodes.rightCols(n_a) = a.nodes.colwise() + Vec3(0.05, 0, 0);
  for (const auto& tet : a.tets)
    both.tets.push_back({tet[0] + static_cast<int>(n_a), tet[1] + static_cast<int>(n_a), tet[2] + static_cast<int>(n_a),
                         tet[3] + static_cast<int>(n_a)});
  both.sets = {{"x0", a.sets.at("x0")}};
  const model::FemModel model = model::build_fem_model(both, fem::material_preset("paper"), {"x0"}, {});
  const roi::RoiSpec spec{
      .kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0.01, 0.005, 0.005), .radius = 0, .count = 5, .set = {}};
  const auto p = roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(both, *model.dofs, spec));
  try {
    ReducedModel condensed(model.system, p, *model.dofs);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("static part K_ss is singular"), std::string::npos) << message;
    // When a node is named, it is one of the loose box's (CHOLMOD's column mapped back to A's).
    if (const auto at = message.find("at node "); at != std::string::npos) {
      EXPECT_GE(std::stol(message.substr(at + 8)), n_a) << message;
    }
    std::printf("%s\n", message.c_str());
  }
}

}  // namespace
}  // namespace roifem::condensation
