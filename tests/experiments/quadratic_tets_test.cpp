// Quadratic tetrahedra on a linear mesh (experiments/quadratic_tets.hpp): midpoints where they
// belong, CalculiX's node order, and the set loads and means of 6-node facets against the linear
// mesh's own (fem/loads.hpp) on fields both represent exactly.
#include "experiments/quadratic_tets.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "fem/loads.hpp"
#include "mesh/gmsh_reader.hpp"

namespace roifem::experiments {
namespace {

class QuadraticBrain : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new mesh::TetMesh(mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh"));
    q_ = new QuadraticTets(quadratic_tets(*mesh_));
  }
  static void TearDownTestSuite() {
    delete q_;
    delete mesh_;
  }
  static mesh::TetMesh* mesh_;
  static QuadraticTets* q_;
};
mesh::TetMesh* QuadraticBrain::mesh_ = nullptr;
QuadraticTets* QuadraticBrain::q_ = nullptr;

TEST_F(QuadraticBrain, EveryEdgeHasOneMidpointInCalculixOrder) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  EXPECT_EQ(q.corner_nodes, m.num_nodes());
  EXPECT_EQ(q.nodes.cols(), m.num_nodes() + static_cast<Index>(q.edges.size()));
  // Euler for a tetrahedral ball: V - E + F - T = 1 (F: all triangles, interior ones counted once).
  const Index edges = static_cast<Index>(q.edges.size()), boundary = static_cast<Index>(mesh::boundary_faces(m).size());
  const Index faces = (4 * m.num_tets() + boundary) / 2;
  EXPECT_EQ(m.num_nodes() - edges + faces - m.num_tets(), 1);
  const int pairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& t = q.tets[e];
    for (int k = 0; k < 4; ++k) ASSERT_EQ(t[k], m.tets[e][k]);
    for (int k = 0; k < 6; ++k) {
      const Vec3 mid = 0.5 * (m.node(t[pairs[k][0]]) + m.node(t[pairs[k][1]]));
      ASSERT_LT((q.nodes.col(t[4 + k]) - mid).norm(), 1e-15) << "tetrahedron " << e << ", edge " << k;
    }
  }
  EXPECT_EQ(q.midpoint(m.tets[0][0], m.tets[0][0]), -1);
}

TEST_F(QuadraticBrain, SetForcesAndMeansAgreeWithTheLinearMeshOnAffineFields) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  const Vec3 total(0.3, -0.1, 0.2);
  const Vector f = quadratic_set_force(m, q, "opening_right", total);
  Vec3 sum = Vec3::Zero();
  for (Index n = 0; n < q.nodes.cols(); ++n) {
    sum += f.segment<3>(3 * n);
    if (n < q.corner_nodes) {
      ASSERT_EQ(f.segment<3>(3 * n).norm(), 0.0) << "corner " << n;  // the midside nodes carry it all
    }
  }
  EXPECT_LT((sum - total).norm(), 1e-15);

  // An affine field: the mean over the wall is the field at the wall's centroid, for both meshes.
  Mat3 A;
  A << 1, 2, -1, 0.5, -2, 3, 1, 1, 4;
  const Vec3 b(1e-3, -2e-3, 5e-4);
  Vector u_linear(3 * m.num_nodes()), u_quadratic(3 * q.nodes.cols());
  for (Index n = 0; n < m.num_nodes(); ++n) u_linear.segment<3>(3 * n) = A * m.nodes.col(n) + b;
  for (Index n = 0; n < q.nodes.cols(); ++n) u_quadratic.segment<3>(3 * n) = A * q.nodes.col(n) + b;
  for (const char* set : {"opening_left", "opening_right", "opening_floor"}) {
    const Vec3 linear = fem::set_mean_displacement(m, set, u_linear);
    EXPECT_LT((quadratic_set_mean_displacement(m, q, set, u_quadratic) - linear).norm(), 1e-14 * linear.norm()) << set;
  }
  EXPECT_THROW(quadratic_set_force(m, q, "base", total), InputError);  // a volume, no facets
}

TEST_F(QuadraticBrain, NodesOnASetAreItsNodesAndTheMidpointsBetweenThem) {
  const auto& m = *mesh_;
  const auto& q = *q_;
  const auto& wall = m.set("opening_left");
  const std::vector<int> nodes = quadratic_nodes_on(q, wall.nodes);
  // The wall is flat: its nodes, and the midpoints of the edges between two of them (its
  // triangles' edges and no others), all on the plane x = -2 mm.
  std::vector<std::pair<int, int>> wall_edges;
  for (const auto& t : wall.triangles)
    for (int k = 0; k < 3; ++k) wall_edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  std::sort(wall_edges.begin(), wall_edges.end());
  wall_edges.erase(std::unique(wall_edges.begin(), wall_edges.end()), wall_edges.end());
  EXPECT_EQ(nodes.size(), wall.nodes.size() + wall_edges.size());
  for (const int n : nodes) EXPECT_NEAR(q.nodes(0, n), -2 * mm, 1e-9) << n;
}

}  // namespace
}  // namespace roifem::experiments
