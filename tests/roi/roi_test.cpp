// SPDX-License-Identifier: GPL-3.0-or-later
// ROI selection and the dof partition it induces (roi.hpp), and where nodes' components sit in the
// full and the reduced numbering (node_dofs.hpp), checked by brute force on the shipped brain.
#include "roi/roi.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "common/errors.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "roi/node_dofs.hpp"
#include "test_models.hpp"

namespace roifem::roi {
namespace {

using test::nearest;
using test::PaperBrain;

TEST(RoiSelection, EmptyRoiIsAModelErrorNamingTheRoi) {
  const PaperBrain brain;
  const RoiSpec far{.kind = RoiSpec::Kind::ball, .center = Vec3(1, 1, 1), .radius = 0.001, .count = 0, .set = {}};
  try {
    select_roi_nodes(brain.mesh, *brain.model.dofs, far);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("contains no free node"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ball of radius 1 mm"), std::string::npos) << e.what();
  }
}

TEST(RoiSelection, NearestTargetOutsideTheMeshIsAModelErrorNamingTargetAndBox) {
  const PaperBrain brain;
  RoiSpec spec = nearest(100);
  spec.center = Vec3(0, 0, 40);  // 40 m: millimetres mistaken for metres
  try {
    select_roi_nodes(brain.mesh, *brain.model.dofs, spec);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("100 nodes nearest (0, 0, 40000) mm"), std::string::npos) << message;
    EXPECT_NE(message.find("lies outside the mesh"), std::string::npos) << message;
    EXPECT_NE(message.find("brain-800.msh"), std::string::npos) << message;
  }
}

TEST(RoiSelection, NearestPicksTheClosestFreeNodes) {
  const PaperBrain brain;
  const auto spec = nearest(50);
  const auto roi_nodes = select_roi_nodes(brain.mesh, *brain.model.dofs, spec);
  ASSERT_EQ(roi_nodes.size(), 50u);
  double farthest_in = 0;
  for (int n : roi_nodes) farthest_in = std::max(farthest_in, (brain.mesh.node(n) - spec.center).norm());
  std::vector<bool> in(static_cast<std::size_t>(brain.mesh.num_nodes()), false);
  for (int n : roi_nodes) in[static_cast<std::size_t>(n)] = true;
  for (int n = 0; n < brain.mesh.num_nodes(); ++n)
    if (!in[static_cast<std::size_t>(n)] && brain.model.dofs->free_dof(n, 0) >= 0) {
      EXPECT_GE((brain.mesh.node(n) - spec.center).norm(), farthest_in);
    }
}

TEST(RoiSelection, FreeNodesAreThoseWithAFreeComponentAndTheBaseIsNotAmongThem) {
  const PaperBrain brain;
  const std::vector<int> free = free_nodes(brain.mesh, brain.dofs());
  const auto& base = brain.mesh.set("base").nodes;
  EXPECT_EQ(free.size() + base.size(), static_cast<std::size_t>(brain.mesh.num_nodes()));
  for (int n : base) EXPECT_FALSE(std::binary_search(free.begin(), free.end(), n)) << n;
  EXPECT_TRUE(std::is_sorted(free.begin(), free.end()));
}

TEST(RoiSelection, BallHoldsExactlyTheFreeNodesWithinItsRadius) {
  const PaperBrain brain;
  const RoiSpec ball{.kind = RoiSpec::Kind::ball, .center = Vec3(0, 0, 0.04), .radius = 0.03, .count = 0, .set = {}};
  const std::vector<int> roi = select_roi_nodes(brain.mesh, brain.dofs(), ball);
  std::vector<int> expected;
  for (int n : free_nodes(brain.mesh, brain.dofs()))
    if ((brain.mesh.node(n) - ball.center).norm() <= ball.radius) expected.push_back(n);
  EXPECT_EQ(roi, expected);
  EXPECT_GT(roi.size(), 10u);
}

TEST(RoiSelection, NamedSetGivesItsFreeNodes) {
  const PaperBrain brain;
  const RoiSpec spec{.kind = RoiSpec::Kind::set, .center = Vec3::Zero(), .radius = 0, .count = 0, .set = "opening_left"};
  EXPECT_EQ(select_roi_nodes(brain.mesh, brain.dofs(), spec), brain.mesh.set("opening_left").nodes);
}

TEST(Partition, SplitsTheFreeDofsAndTheInterfaceIsWhereKCouplesThem) {
  const PaperBrain brain;
  const SparseMatrix& K = brain.model.system.K;
  const Partition p = partition_dofs(K, brain.dofs(), select_roi_nodes(brain.mesh, brain.dofs(), nearest(228)));
  ASSERT_EQ(p.d.size(), 3 * 228u);
  // d and s: disjoint, ascending, together every free dof once.
  std::vector<Index> all = p.d;
  all.insert(all.end(), p.s.begin(), p.s.end());
  std::sort(all.begin(), all.end());
  ASSERT_EQ(static_cast<Index>(all.size()), brain.dofs().num_free());
  for (Index i = 0; i < static_cast<Index>(all.size()); ++i) ASSERT_EQ(all[static_cast<std::size_t>(i)], i);
  EXPECT_TRUE(std::is_sorted(p.d.begin(), p.d.end()));
  EXPECT_TRUE(std::is_sorted(p.s.begin(), p.s.end()));
  // The interface, by brute force: the positions in d of dofs with a non-zero K entry in an s column.
  const std::set<Index> s_dofs(p.s.begin(), p.s.end());
  std::set<Index> coupled;
  for (Index col = 0; col < K.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(K, col); it; ++it)
      if (it.value() != 0 && s_dofs.count(it.col()) && !s_dofs.count(it.row())) coupled.insert(it.row());
  std::vector<Index> expected;
  for (std::size_t k = 0; k < p.d.size(); ++k)
    if (coupled.count(p.d[k])) expected.push_back(static_cast<Index>(k));
  EXPECT_EQ(p.interface, expected);
  EXPECT_GT(p.interface.size(), 30u);
  EXPECT_LT(p.interface.size(), p.d.size());
}

TEST(NodeDofs, ReducedPositionsPointAtTheSameFreeDofsAndFixedComponentsAreMarked) {
  const PaperBrain brain;
  const Partition p = partition_dofs(brain.model.system.K, brain.dofs(), select_roi_nodes(brain.mesh, brain.dofs(), nearest(50)));
  const NodeDofs full = node_dofs_in_full(p.roi_nodes, brain.dofs());
  const NodeDofs reduced = node_dofs_in_reduced(p.roi_nodes, p, brain.dofs());
  ASSERT_EQ(full.size(), 50u);
  for (std::size_t n = 0; n < full.size(); ++n)
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(full[n][c], brain.dofs().free_dof(p.roi_nodes[n], static_cast<int>(c)));
      EXPECT_EQ(p.d[static_cast<std::size_t>(reduced[n][c])], full[n][c]);
    }
  // A base node is fixed: -1 in both numberings; a static node has no place in the reduced one.
  const int base_node = brain.mesh.set("base").nodes.front();
  EXPECT_EQ(node_dofs_in_full({base_node}, brain.dofs())[0], (std::array<Index, 3>{-1, -1, -1}));
  const std::vector<int> free = free_nodes(brain.mesh, brain.dofs());
  const auto outside = std::find_if(free.begin(), free.end(),
                                    [&](int n) { return !std::binary_search(p.roi_nodes.begin(), p.roi_nodes.end(), n); });
  ASSERT_NE(outside, free.end());
  EXPECT_EQ(node_dofs_in_reduced({*outside}, p, brain.dofs())[0], (std::array<Index, 3>{-1, -1, -1}));
}

}  // namespace
}  // namespace roifem::roi
