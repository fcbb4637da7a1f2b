// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/assembly.hpp"
#include "fem/loads.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <filesystem>

#include "common/errors.hpp"
#include "fem/static_solve.hpp"
#include "fem/tet4.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"

namespace roifem::fem {
namespace {

const std::filesystem::path mesh_dir = ROIFEM_MESH_DIR;

/// Independent reference: all 144 entries of every element as triplets over the full 3N dofs,
/// then the free-free block picked out through the DofMap.
SparseMatrix reference_stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& m) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& t : mesh.tets) {
    const auto Ke = tet4_stiffness(tet4_geometry(mesh.node(t[0]), mesh.node(t[1]), mesh.node(t[2]), mesh.node(t[3])), m);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int r = dofs.free_dof(t[static_cast<std::size_t>(a)], i);
            const int c = dofs.free_dof(t[static_cast<std::size_t>(b)], j);
            if (r >= 0 && c >= 0) triplets.emplace_back(r, c, Ke(3 * a + i, 3 * b + j));
          }
  }
  SparseMatrix K(dofs.num_free(), dofs.num_free());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

TEST(Assembly, PatternAssemblyEqualsTripletAssemblyWithMixedConstraints) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(1, 1, 1, 0.3);
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh.set("x0").nodes) constraints.fix_node(n);
  for (int n : mesh.set("y1").nodes) constraints.prescribe(n, 1, 0.01);  // one component only
  const DofMap dofs(constraints);
  const Material m = Material::from_young_poisson(3000, 0.45, 1000, 0);
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(m);
  const SparseMatrix R = reference_stiffness(mesh, dofs, m);
  EXPECT_LE((K - R).norm(), 1e-12 * R.norm());
  EXPECT_LE((K - SparseMatrix(K.transpose())).norm(), 1e-12 * K.norm());
}

TEST(Assembly, ThreadsFillTheirOwnColumnsSoAnyCountGivesTheSameMatrixBitForBit) {
  // The suite runs one thread per test (OMP_NUM_THREADS=1 in the test presets: two tests at once on
  // two cores); the threaded assembly is checked here, against one thread, on the shipped brain.
  const mesh::TetMesh mesh = mesh::read_mesh((mesh_dir / "brain-800.msh").string());
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh.set("base").nodes) constraints.fix_node(n);
  const DofMap dofs(constraints);
  const Material m = material_preset("paper");
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const SparseMatrix one = StiffnessAssembler(mesh, dofs).stiffness(m);
  omp_set_num_threads(3);
  const SparseMatrix three = StiffnessAssembler(mesh, dofs).stiffness(m);
  omp_set_num_threads(before);
  ASSERT_EQ(one.nonZeros(), three.nonZeros());
  EXPECT_EQ(Eigen::Map<const Vector>(one.valuePtr(), one.nonZeros()),
            Eigen::Map<const Vector>(three.valuePtr(), three.nonZeros()));
  EXPECT_LE((one - reference_stiffness(mesh, dofs, m)).norm(), 1e-12 * one.norm());
}

TEST(Assembly, PrescribedLoadEqualsMinusKfpTimesUp) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(3, 3, 3, 1, 1, 1);
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh.set("z0").nodes) constraints.fix_node(n, Vec3(0.01 * n, -0.02, 0.003 * n));
  const DofMap dofs(constraints);
  const Material m = Material::from_young_poisson(3000, 0.3, 1000, 0);
  // Reference: the full 3N x 3N stiffness times the full vector of prescribed values.
  Constraints none(mesh.num_nodes());
  const DofMap all(none);
  const Vector full_force = StiffnessAssembler(mesh, all).stiffness(m) * dofs.prescribed();
  const Vector expected = -dofs.restrict_to_free(full_force);
  EXPECT_LE((StiffnessAssembler(mesh, dofs).prescribed_load(m) - expected).norm(), 1e-12 * expected.norm());
}

TEST(LumpedMass, SumsToDensityTimesVolumeOnEveryShippedMesh) {
  int meshes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(mesh_dir)) {
    if (entry.path().extension() != ".msh") continue;
    const mesh::TetMesh mesh = mesh::read_mesh(entry.path());
    const double rho = 1040;
    const Vector m = lumped_node_mass(mesh, rho);
    EXPECT_NEAR(m.sum(), rho * mesh::total_volume(mesh), 1e-12 * rho * mesh::total_volume(mesh)) << entry.path();
    EXPECT_GT(m.minCoeff(), 0) << entry.path();
    ++meshes;
  }
  EXPECT_GE(meshes, 1);
}

TEST(ShippedBrain, VolumeIsTheEllipsoidLessTheOpening) {
  const mesh::TetMesh mesh = mesh::read_mesh(mesh_dir / "brain-800.msh");
  const double ellipsoid = 4.0 / 3.0 * M_PI * 0.070 * 0.085 * 0.050;
  // The faceted surface of a coarse mesh lies inside the ellipsoid: a few percent less volume.
  EXPECT_GT(mesh::total_volume(mesh), 0.95 * ellipsoid);
  EXPECT_LT(mesh::total_volume(mesh), ellipsoid);
  EXPECT_GE(mesh.num_nodes(), 780);
  EXPECT_LE(mesh.num_nodes(), 820);
  for (const char* set : {"brain", "base", "opening_left", "opening_right", "opening_floor"})
    EXPECT_FALSE(mesh.set(set).nodes.empty()) << set;
}

TEST(ShippedBrain, StiffnessWithBaseFixedIsPositiveDefiniteAndPaperModesAreSlow) {
  const mesh::TetMesh mesh = mesh::read_mesh(mesh_dir / "brain-800.msh");
  Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "base");
  const DofMap dofs(constraints);
  const Material paper = material_preset("paper");
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(paper);
  solvers::Cholesky cholesky;
  EXPECT_NO_THROW(factorize_stiffness(cholesky, K, dofs));
  // Generalized eigenproblem K phi = w^2 M phi with lumped M: eigenvalues of M^-1/2 K M^-1/2.
  const Vector inv_sqrt_m = lumped_mass(mesh, dofs, paper.rho).cwiseSqrt().cwiseInverse();
  const DenseMatrix A = inv_sqrt_m.asDiagonal() * DenseMatrix(K) * inv_sqrt_m.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(A, Eigen::EigenvaluesOnly);
  ASSERT_GT(eig.eigenvalues()[0], 0);
  const Vector w = eig.eigenvalues().cwiseSqrt();
  std::printf("paper preset, brain-800, base fixed: lowest w = %.3f %.3f %.3f %.3f %.3f %.3f rad/s, highest %.1f rad/s\n", w[0],
              w[1], w[2], w[3], w[4], w[5], w[w.size() - 1]);
  // The paper's error curves settle in about 50 steps of 0.05 s: lowest modes near 2 rad/s.
  EXPECT_GT(w[0], 0.5);
  EXPECT_LT(w[0], 4.0);
}

TEST(StaticSolve, NoFixedNodeIsAModelErrorAboutRigidModes) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(2, 2, 2, 1, 1, 1);
  const DofMap dofs(Constraints(mesh.num_nodes()));
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(Material::from_young_poisson(1e3, 0.3, 1e3, 0));
  try {
    solve_static(K, Vector::Ones(dofs.num_free()), dofs);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("rigid"), std::string::npos) << e.what();
  }
}

TEST(StaticSolve, TooFewConstraintsAreDetectedAsSingular) {
  // One node fixed: the body can still rotate about it.
  const mesh::TetMesh mesh = mesh::structured_box_mesh(2, 2, 2, 1, 1, 1);
  Constraints constraints(mesh.num_nodes());
  constraints.fix_node(0);
  const DofMap dofs(constraints);
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(Material::from_young_poisson(1e3, 0.3, 1e3, 0));
  EXPECT_THROW(solve_static(K, Vector::Ones(dofs.num_free()), dofs), ModelError);
}

}  // namespace
}  // namespace roifem::fem

namespace roifem::fem {
namespace {

TEST(Loads, GravitySumsToTotalMassTimesG) {
  const mesh::TetMesh mesh = mesh::read_mesh(mesh_dir / "brain-800.msh");
  const Vec3 g(0, 0, -9.81);
  const Vector f = gravity_force(mesh, 1040, g);
  Vec3 total = Vec3::Zero();
  for (Index n = 0; n < mesh.num_nodes(); ++n) total += f.segment<3>(3 * n);
  const Vec3 expected = 1040 * mesh::total_volume(mesh) * g;
  EXPECT_LT((total - expected).norm(), 1e-12 * expected.norm());
}

TEST(Loads, SetForceSumsToTheTotalAndActsOnlyOnTheSet) {
  const mesh::TetMesh mesh = mesh::read_mesh(mesh_dir / "brain-800.msh");
  const Vector f = set_force(mesh, "opening_left", Vec3(-0.02, 0.001, 0));
  Vec3 total = Vec3::Zero();
  const auto& nodes = mesh.set("opening_left").nodes;
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    total += f.segment<3>(3 * n);
    if (!std::binary_search(nodes.begin(), nodes.end(), static_cast<int>(n))) {
      EXPECT_TRUE(f.segment<3>(3 * n).isZero(0));
    }
  }
  EXPECT_LT((total - Vec3(-0.02, 0.001, 0)).norm(), 1e-15);
}

}  // namespace
}  // namespace roifem::fem
