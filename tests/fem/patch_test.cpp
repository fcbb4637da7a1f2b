// SPDX-License-Identifier: GPL-3.0-or-later
// The patch test: an affine displacement imposed on the boundary of an unstructured mesh with
// distorted interior nodes must be reproduced exactly inside, with constant strain.
#include <gtest/gtest.h>

#include <random>

#include "fem/assembly.hpp"
#include "fem/static_solve.hpp"
#include "fem/tet4.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::fem {
namespace {

TEST(PatchTest, AffineBoundaryDisplacementIsReproducedInsideWithConstantStrain) {
  mesh::TetMesh mesh = mesh::unstructured_box_mesh(1.0, 0.8, 0.6, 0.2);
  const std::vector<int> boundary = mesh::boundary_nodes(mesh);
  std::vector<bool> on_boundary(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (int n : boundary) on_boundary[static_cast<std::size_t>(n)] = true;

  // Distort the interior nodes by up to 20% of the element size, keeping every element valid.
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  int interior = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (!on_boundary[static_cast<std::size_t>(n)]) {
      mesh.nodes.col(n) += Vec3(jitter(rng), jitter(rng), jitter(rng));
      ++interior;
    }
  ASSERT_GT(interior, 10);
  mesh::check_mesh(mesh);

  Mat3 A;
  A << 1e-3, 2e-3, -1e-3, 0.5e-3, -2e-3, 3e-3, 1e-3, 1e-3, 4e-3;
  const Vec3 b(1e-3, -2e-3, 0.5e-3);
  Constraints constraints(mesh.num_nodes());
  for (int n : boundary) constraints.fix_node(n, A * mesh.node(n) + b);
  const DofMap dofs(constraints);
  const Material material = Material::from_young_poisson(3000, 0.45, 1000, 0);
  const StiffnessAssembler assembler(mesh, dofs);
  const Vector u = dofs.expand(solve_static(assembler.stiffness(material), assembler.prescribed_load(material), dofs));

  double worst = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) worst = std::max(worst, (u.segment<3>(3 * n) - (A * mesh.node(n) + b)).norm());
  EXPECT_LT(worst / A.norm(), 1e-10);
  RecordProperty("patch_displacement_error", std::to_string(worst / A.norm()));
  std::printf("patch test: %d interior nodes, max |u - (A x + b)| / |A| = %.3e\n", interior, worst / A.norm());

  const Mat3 eps = 0.5 * (A + A.transpose());
  Eigen::Matrix<double, 6, 1> expected;
  expected << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(1, 2), 2 * eps(0, 2), 2 * eps(0, 1);
  double worst_strain = 0;
  for (const auto& t : mesh.tets) {
    Eigen::Matrix<double, 12, 1> ue;
    for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * t[static_cast<std::size_t>(a)]);
    const auto g = tet4_geometry(mesh.node(t[0]), mesh.node(t[1]), mesh.node(t[2]), mesh.node(t[3]));
    worst_strain = std::max(worst_strain, (tet4_strain(g, ue) - expected).norm());
  }
  EXPECT_LT(worst_strain / expected.norm(), 1e-10);
  std::printf("patch test: max strain error / |strain| = %.3e\n", worst_strain / expected.norm());
}

}  // namespace
}  // namespace roifem::fem
