// SPDX-License-Identifier: GPL-3.0-or-later
// A linear mesh made quadratic (mesh/quadratic_mesh.hpp): midpoints where they belong in Gmsh's and
// CalculiX's order, sets that gain the midpoints between their nodes, set loads and means of 6-node
// facets against the linear mesh's own (fem/loads.hpp) on fields both represent exactly, and
// interpolation that is exact for quadratic fields.
#include "mesh/quadratic_mesh.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "fem/loads.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/point_locator.hpp"

namespace roifem::mesh {
namespace {

class QuadraticBrain : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new TetMesh(read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh"));
    q_ = new TetMesh(with_midside_nodes(*mesh_));
  }
  static void TearDownTestSuite() {
    delete q_;
    delete mesh_;
  }
  static TetMesh* mesh_;
  static TetMesh* q_;
};
TetMesh* QuadraticBrain::mesh_ = nullptr;
TetMesh* QuadraticBrain::q_ = nullptr;

TEST_F(QuadraticBrain, EveryEdgeHasOneMidpointInCalculixOrder) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  EXPECT_TRUE(q.is_quadratic());
  EXPECT_FALSE(m.is_quadratic());
  EXPECT_EQ(q.num_vertices(), m.num_nodes());
  EXPECT_EQ(q.num_nodes(), m.num_nodes() + static_cast<Index>(q.midside.edges.size()));
  // Euler for a tetrahedral ball: V - E + F - T = 1 (F: all triangles, interior ones counted once).
  const Index edges = static_cast<Index>(q.midside.edges.size()), boundary = static_cast<Index>(boundary_faces(m).size());
  const Index faces = (4 * m.num_tets() + boundary) / 2;
  EXPECT_EQ(m.num_nodes() - edges + faces - m.num_tets(), 1);
  const int pairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& t = q.tets[e];
    for (int k = 0; k < 4; ++k) ASSERT_EQ(t[k], m.tets[e][k]);
    for (int k = 0; k < 6; ++k) {
      const Vec3 mid = 0.5 * (m.node(t[pairs[k][0]]) + m.node(t[pairs[k][1]]));
      ASSERT_LT((q.node(q.midside.of_tet[e][k]) - mid).norm(), 1e-15) << "tetrahedron " << e << ", edge " << k;
    }
  }
  EXPECT_EQ(q.midside.at(m.tets[0][0], m.tets[0][0]), -1);
  EXPECT_THROW(with_midside_nodes(q), Error);
  // The boundary's nodes: the linear boundary's and its edges' midpoints, so more than before.
  EXPECT_GT(boundary_nodes(q).size(), 3 * boundary_nodes(m).size());
}

TEST_F(QuadraticBrain, SetForcesAndMeansAgreeWithTheLinearMeshOnAffineFields) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  const Vec3 total(0.3, -0.1, 0.2);
  const Vector f = fem::set_force(q, "opening_right", total);
  Vec3 sum = Vec3::Zero();
  for (Index n = 0; n < q.num_nodes(); ++n) {
    sum += f.segment<3>(3 * n);
    if (n < q.num_vertices()) {
      ASSERT_EQ(f.segment<3>(3 * n).norm(), 0.0) << "corner " << n;  // the midside nodes carry it all
    }
  }
  EXPECT_LT((sum - total).norm(), 1e-15);
  // A volume set's force by the HRZ fractions: positive shares summing to the total.
  const Vector f_base = fem::set_force(q, "base", total);
  Vec3 base_sum = Vec3::Zero();
  for (Index n = 0; n < q.num_nodes(); ++n) base_sum += f_base.segment<3>(3 * n);
  EXPECT_LT((base_sum - total).norm(), 1e-15);

  // An affine field: the mean over the wall is the field at the wall's centroid, for both meshes.
  Mat3 A;
  A << 1, 2, -1, 0.5, -2, 3, 1, 1, 4;
  const Vec3 b(1e-3, -2e-3, 5e-4);
  Vector u_linear(3 * m.num_nodes()), u_quadratic(3 * q.num_nodes());
  for (Index n = 0; n < m.num_nodes(); ++n) u_linear.segment<3>(3 * n) = A * m.nodes.col(n) + b;
  for (Index n = 0; n < q.num_nodes(); ++n) u_quadratic.segment<3>(3 * n) = A * q.nodes.col(n) + b;
  for (const char* set : {"opening_left", "opening_right", "opening_floor"}) {
    const Vec3 linear = fem::set_mean_displacement(m, set, u_linear);
    EXPECT_LT((fem::set_mean_displacement(q, set, u_quadratic) - linear).norm(), 1e-14 * linear.norm()) << set;
  }
}

TEST_F(QuadraticBrain, SetsGainTheMidpointsBetweenTheirNodes) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  const auto& wall = m.set("opening_left");
  const std::vector<int>& nodes = q.set("opening_left").nodes;
  // The wall is flat: its nodes, and the midpoints of the edges between two of them (its
  // triangles' edges and no others), all on the plane x = -2 mm.
  std::vector<std::pair<int, int>> wall_edges;
  for (const auto& t : wall.triangles)
    for (int k = 0; k < 3; ++k) wall_edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  std::sort(wall_edges.begin(), wall_edges.end());
  wall_edges.erase(std::unique(wall_edges.begin(), wall_edges.end()), wall_edges.end());
  EXPECT_EQ(nodes.size(), wall.nodes.size() + wall_edges.size());
  EXPECT_TRUE(std::is_sorted(nodes.begin(), nodes.end()));
  for (const int n : nodes) EXPECT_NEAR(q.nodes(0, n), -2 * mm, 1e-9) << n;
}

TEST_F(QuadraticBrain, InterpolationIsExactForQuadraticFields) {
  const auto& q = *q_;
  auto field = [](const Vec3& x) { return Vec3(x.x() * x.y(), x.z() * x.z() - x.x(), 3 * x.y() * x.y() + x.z()); };
  Vector u(3 * q.num_nodes());
  for (Index n = 0; n < q.num_nodes(); ++n) u.segment<3>(3 * n) = field(q.nodes.col(n));
  const PointLocator locator(q);
  for (const std::size_t e : {0UL, 700UL, 2500UL}) {  // points inside three tetrahedra
    const auto& t = q.tets[e];
    const Vec3 p = 0.1 * q.node(t[0]) + 0.2 * q.node(t[1]) + 0.3 * q.node(t[2]) + 0.4 * q.node(t[3]);
    const PointLocation at = locator.locate(p);
    ASSERT_EQ(at.outside_distance, 0.0);
    EXPECT_LT((PointLocator::interpolate(at, u) - field(p)).norm(), 1e-14 * field(p).norm()) << p.transpose();
  }
}

}  // namespace
}  // namespace roifem::mesh
