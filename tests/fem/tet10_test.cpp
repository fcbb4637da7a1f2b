// SPDX-License-Identifier: GPL-3.0-or-later
// The 10-node tetrahedron (fem/tet10.hpp): its shape functions, its element matrix (symmetric,
// six rigid-body modes, rank 24), the assembled K against a triplet scatter of element matrices,
// HRZ's lumped mass, and the higher-order patch test: a field quadratic in x with no body force
// (pure bending) imposed on the boundary is reproduced exactly inside, which the linear
// tetrahedron cannot do.
#include "fem/tet10.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "fem/assembly.hpp"
#include "fem/static_solve.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "test_support.hpp"

namespace roifem::fem {
namespace {

const Material tissue = Material::from_young_poisson(3000, 0.45, 1000, 0);

/// A skewed tetrahedron, positively oriented.
std::array<Vec3, 4> skewed() { return {Vec3(0, 0, 0), Vec3(1.2, 0.1, -0.1), Vec3(0.3, 0.9, 0.2), Vec3(0.2, 0.3, 1.1)}; }

/// The barycentric coordinates of the 10 nodes.
std::array<Eigen::Vector4d, 10> node_coordinates() {
  std::array<Eigen::Vector4d, 10> L{};
  for (int i = 0; i < 4; ++i) L[i] = Eigen::Vector4d::Unit(i);
  for (std::size_t k = 0; k < tet10_edges.size(); ++k)
    L[4 + k] = 0.5 * (Eigen::Vector4d::Unit(tet10_edges[k][0]) + Eigen::Vector4d::Unit(tet10_edges[k][1]));
  return L;
}

TEST(Tet10, ShapeFunctionsAreNodalAndReproduceQuadratics) {
  const auto L = node_coordinates();
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) EXPECT_NEAR(tet10_shape(L[a])[b], a == b ? 1.0 : 0.0, 1e-15) << a << ", " << b;
  // At a random point: they sum to 1 and interpolate q(L) = L0 L3 + 2 L1^2 - L2 exactly.
  auto q = [](const Eigen::Vector4d& l) { return l[0] * l[3] + 2 * l[1] * l[1] - l[2]; };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> draw(0, 1);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::Vector4d p(draw(rng), draw(rng), draw(rng), draw(rng));
    p /= p.sum();
    const auto N = tet10_shape(p);
    double interpolated = 0;
    for (int a = 0; a < 10; ++a) interpolated += N[a] * q(L[a]);
    EXPECT_NEAR(N.sum(), 1.0, 1e-15);
    EXPECT_NEAR(interpolated, q(p), 1e-14);
  }
}

TEST(Tet10, ElementMatrixIsSymmetricWithSixRigidModesAndRank24) {
  const auto x = skewed();
  const Tet10Geometry g = tet10_geometry(x[0], x[1], x[2], x[3]);
  const Tet10Matrix K = tet10_stiffness(g, tissue);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  // The node positions, for the rigid motions: corners, then midpoints.
  std::array<Vec3, 10> X{};
  for (int i = 0; i < 4; ++i) X[i] = x[i];
  for (std::size_t k = 0; k < tet10_edges.size(); ++k) X[4 + k] = 0.5 * (x[tet10_edges[k][0]] + x[tet10_edges[k][1]]);
  for (int mode = 0; mode < 6; ++mode) {
    Eigen::Matrix<double, 30, 1> u;
    for (int a = 0; a < 10; ++a) u.segment<3>(3 * a) = mode < 3 ? Vec3(Vec3::Unit(mode)) : Vec3(Vec3::Unit(mode - 3).cross(X[a]));
    EXPECT_LT((K * u).norm(), 1e-12 * K.norm() * u.norm()) << "rigid mode " << mode;
  }
  const Eigen::SelfAdjointEigenSolver<Tet10Matrix> eig(K);
  const double largest = eig.eigenvalues().maxCoeff();
  int positive = 0;
  for (int i = 0; i < 30; ++i) positive += eig.eigenvalues()[i] > 1e-10 * largest;
  EXPECT_EQ(positive, 24);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * largest);
}

TEST(Tet10, AssemblyEqualsAScatterOfElementMatricesAndTheMassIsHrzs) {
  const mesh::TetMesh q = mesh::with_midside_nodes(mesh::unstructured_box_mesh(1, 0.8, 0.6, 0.3));
  Constraints constraints(q.num_nodes());
  for (int n : q.set("x0").nodes) constraints.fix_node(n);
  for (int n : q.set("y1").nodes) constraints.prescribe(n, 1, 0.01);  // one component only
  const DofMap dofs(constraints);
  const SparseMatrix K = StiffnessAssembler(q, dofs).stiffness(tissue);
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t e = 0; e < q.tets.size(); ++e) {
    const auto& c = q.tets[e];
    std::array<int, 10> nodes{};
    for (int i = 0; i < 4; ++i) nodes[i] = c[i];
    for (int k = 0; k < 6; ++k) nodes[4 + k] = q.midside.of_tet[e][k];
    const Tet10Matrix Ke = tet10_stiffness(tet10_geometry(q.node(c[0]), q.node(c[1]), q.node(c[2]), q.node(c[3])), tissue);
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (const int r = dofs.free_dof(nodes[a], i), s = dofs.free_dof(nodes[b], j); r >= 0 && s >= 0)
              triplets.emplace_back(r, s, Ke(3 * a + i, 3 * b + j));
  }
  SparseMatrix R(dofs.num_free(), dofs.num_free());
  R.setFromTriplets(triplets.begin(), triplets.end());
  EXPECT_LE((K - R).norm(), 1e-12 * R.norm());

  // The prescribed value's load is -K_fp u_p, here from the element matrices.
  Constraints none(q.num_nodes());
  const DofMap all(none);
  const Vector expected = -dofs.restrict_to_free(StiffnessAssembler(q, all).stiffness(tissue) * dofs.prescribed());
  EXPECT_LE((StiffnessAssembler(q, dofs).prescribed_load(tissue) - expected).norm(), 1e-12 * expected.norm());

  // HRZ: every mass positive, the total the body's, a corner 1/36 and a midpoint 4/27 of each element's.
  const Vector m = lumped_node_mass(q, tissue.rho);
  EXPECT_GT(m.minCoeff(), 0.0);
  EXPECT_NEAR(m.sum(), tissue.rho * 1 * 0.8 * 0.6, 1e-12 * m.sum());
  EXPECT_NEAR(4 * tet10_corner_mass + 6 * tet10_midside_mass, 1.0, 1e-15);
  // The ratio of the consistent mass's diagonal entries, 32 : 6 (8 rho V/105 against rho V/70).
  EXPECT_NEAR(tet10_midside_mass / tet10_corner_mass, 32.0 / 6.0, 1e-14);
}

/// Pure bending of a prism along x (curvature k about y): u = (k x z, -nu k y z, -k/2 (x^2 + nu (z^2 - y^2))).
/// The stress is sigma_xx = E k z alone, divergence-free: no body force, so it is the exact
/// solution for these boundary values.
Vec3 bending(const Vec3& x, double nu) {
  const double k = 1e-2;
  return {k * x.x() * x.z(), -nu * k * x.y() * x.z(), -0.5 * k * (x.x() * x.x() + nu * (x.z() * x.z() - x.y() * x.y()))};
}

double bending_error(const mesh::TetMesh& mesh, const Material& material) {
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh::boundary_nodes(mesh)) constraints.fix_node(n, bending(mesh.node(n), material.poisson()));
  const DofMap dofs(constraints);
  const StiffnessAssembler assembler(mesh, dofs);
  const Vector u = dofs.expand(solve_static(assembler.stiffness(material), assembler.prescribed_load(material), dofs));
  double worst = 0, scale = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 exact = bending(mesh.node(n), material.poisson());
    worst = std::max(worst, (u.segment<3>(3 * n) - exact).norm());
    scale = std::max(scale, exact.norm());
  }
  return worst / scale;
}

TEST(Tet10, PassesTheQuadraticPatchTestOnADistortedMesh) {
  const mesh::TetMesh linear = test::distorted_box(0.2, 42);
  const mesh::TetMesh quadratic = mesh::with_midside_nodes(linear);
  for (const double nu : {0.3, 0.4999}) {
    const Material material = Material::from_young_poisson(3000, nu, 1000, 0);
    const double tet10 = bending_error(quadratic, material), tet4 = bending_error(linear, material);
    std::printf("pure bending, nu = %g: max nodal error / max |u|: tet10 %.2e, tet4 %.2e\n", nu, tet10, tet4);
    EXPECT_LT(tet10, 1e-10) << nu;
    EXPECT_GT(tet4, 1e-3) << nu;  // the linear element is not exact for it
  }
}

}  // namespace
}  // namespace roifem::fem
