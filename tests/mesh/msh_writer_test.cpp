// SPDX-License-Identifier: GPL-3.0-or-later
// write_msh: what it writes, read_mesh reads back the same (nodes, tetrahedra, named sets).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "common/types.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/msh_writer.hpp"
#include "mesh/quality_smoothing.hpp"
#include "test_support.hpp"

namespace roifem::mesh {
namespace {

/// A set's tetrahedra as node lists: the file groups tetrahedra by the sets they belong to, so
/// their order (and index) may change; what they are may not.
std::multiset<Tet> tets_of(const TetMesh& m, const std::vector<int>& indices) {
  std::multiset<Tet> tets;
  for (int e : indices) tets.insert(m.tets[static_cast<std::size_t>(e)]);
  return tets;
}

TEST(MshWriter, ReadBackGivesTheSameMeshAndSets) {
  TetMesh box = structured_box_mesh(3, 2, 2, 0.03, 0.02, 0.02);
  // An overlapping 3D set: half the tetrahedra, so that elements carry different set lists.
  NamedSet half;
  half.dim = 3;
  for (int e = 0; e < box.num_tets(); e += 2) half.tets.push_back(e);
  for (int e : half.tets)
    for (int n : box.tets[static_cast<std::size_t>(e)]) half.nodes.push_back(n);
  std::sort(half.nodes.begin(), half.nodes.end());
  half.nodes.erase(std::unique(half.nodes.begin(), half.nodes.end()), half.nodes.end());
  box.sets["half"] = half;
  test::TempDir dir;
  write_msh(box, dir / "box.msh", mm);
  const TetMesh read = read_mesh(dir / "box.msh");
  ASSERT_EQ(read.num_nodes(), box.num_nodes());
  EXPECT_LT((read.nodes - box.nodes).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(std::multiset<Tet>(read.tets.begin(), read.tets.end()), std::multiset<Tet>(box.tets.begin(), box.tets.end()));
  ASSERT_EQ(read.sets.size(), box.sets.size());
  for (const auto& [name, set] : box.sets) {
    const NamedSet& other = read.set(name);
    EXPECT_EQ(other.dim, set.dim) << name;
    EXPECT_EQ(other.nodes, set.nodes) << name;
    EXPECT_EQ(tets_of(read, other.tets), tets_of(box, set.tets)) << name;
    EXPECT_EQ(other.triangles.size(), set.triangles.size()) << name;
  }
}

TEST(QualitySmoothing, RaisesTheWorstTetrahedronAndKeepsTheBoundary) {
  TetMesh box = structured_box_mesh(4, 4, 4, 1, 1, 1);
  const std::vector<int> boundary = boundary_nodes(box);
  // Pull one interior node almost onto its neighbour: its tetrahedra become slivers.
  int interior = -1;
  for (int n = 0; n < box.num_nodes() && interior < 0; ++n)
    if (!std::binary_search(boundary.begin(), boundary.end(), n)) interior = n;
  // Move it 95% of the way to the opposite face of one of its tetrahedra: that one flattens.
  for (const Tet& t : box.tets)
    if (std::find(t.begin(), t.end(), interior) != t.end()) {
      Vec3 face = Vec3::Zero();
      for (int n : t)
        if (n != interior) face += box.node(n) / 3;
      box.nodes.col(interior) += 0.95 * (face - box.node(interior));
      break;
    }
  for (Index e = 0; e < box.num_tets(); ++e) ASSERT_GT(signed_volume(box, e), 0);
  const Eigen::Matrix3Xd before = box.nodes;
  const SmoothingReport report = smooth_poor_tetrahedra(box);
  EXPECT_LT(report.quality_min_before, 0.15);
  EXPECT_GT(report.quality_min_after, 2 * report.quality_min_before);
  for (int n : boundary) EXPECT_EQ(box.nodes.col(n), before.col(n)) << "boundary node " << n;
  for (Index e = 0; e < box.num_tets(); ++e) EXPECT_GT(signed_volume(box, e), 0);
}

}  // namespace
}  // namespace roifem::mesh
