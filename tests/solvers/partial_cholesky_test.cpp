// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/partial_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <random>

#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"

namespace roifem::solvers {
namespace {

/// K of the shipped brain with its base fixed: a real 3D stiffness pattern (about 2000 dofs).
SparseMatrix brain_stiffness() {
  static const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  return model::build_fem_model(mesh, fem::material_preset("paper"), {"base"}, {}).system.K;
}

/// `count` distinct indices below n, in random (unsorted) order.
std::vector<Index> random_indices(Index n, Index count, unsigned seed) {
  std::vector<Index> all(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
  std::mt19937 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(static_cast<std::size_t>(count));
  return all;
}

DenseMatrix dense_block(const DenseMatrix& A, const std::vector<Index>& rows, const std::vector<Index>& cols) {
  DenseMatrix B(static_cast<Index>(rows.size()), static_cast<Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (std::size_t i = 0; i < rows.size(); ++i) B(static_cast<Index>(i), static_cast<Index>(j)) = A(rows[i], cols[j]);
  return B;
}

TEST(PartialCholesky, TrailingBlockOfTheFactorIsTheSchurComplement) {
  const SparseMatrix K = brain_stiffness();
  const DenseMatrix A(K);
  const std::vector<Index> trailing = random_indices(K.rows(), 150, 7);
  PartialCholesky factor(K, trailing);
  const std::vector<Index>& leading = factor.leading();
  ASSERT_EQ(leading.size() + trailing.size(), static_cast<std::size_t>(K.rows()));
  // The independent answer: A_tt - A_tl A_ll^-1 A_lt by a dense Cholesky of A_ll.
  const Eigen::LLT<DenseMatrix> A_ll(dense_block(A, leading, leading));
  ASSERT_EQ(A_ll.info(), Eigen::Success);
  const DenseMatrix A_lt = dense_block(A, leading, trailing);
  const DenseMatrix expected = dense_block(A, trailing, trailing) - A_lt.transpose() * A_ll.solve(A_lt);
  const DenseMatrix S = factor.trailing_schur_complement();
  const double error = (S - expected).norm() / expected.norm();
  std::printf("Schur complement from the factor vs dense: %.2e (relative, %zu trailing of %ld)\n", error, trailing.size(),
              static_cast<long>(K.rows()));
  EXPECT_LT(error, 1e-11);
}

TEST(PartialCholesky, LeadingBlockSolvesWithTheLeadingMatrix) {
  const SparseMatrix K = brain_stiffness();
  PartialCholesky factor(K, random_indices(K.rows(), 90, 11));
  const DenseMatrix A_ll = dense_block(DenseMatrix(K), factor.leading(), factor.leading());
  const Vector b = Vector::Random(A_ll.rows());
  const Vector x = factor.solve_leading(b);
  const double residual = (A_ll * x - b).norm() / b.norm();
  const Vector expected = A_ll.llt().solve(b);
  std::printf("leading solve: residual %.2e, vs dense %.2e\n", residual, (x - expected).norm() / expected.norm());
  EXPECT_LT(residual, 1e-12);
  EXPECT_LT((x - expected).norm() / expected.norm(), 1e-9);
}

TEST(PartialCholesky, NoTrailingIndicesIsAPlainCholesky) {
  const SparseMatrix K = brain_stiffness();
  PartialCholesky factor(K, {});
  EXPECT_EQ(factor.trailing_schur_complement().size(), 0);
  const Vector b = Vector::Ones(K.rows());
  Cholesky plain;
  plain.compute(K);
  const Vector expected = plain.solve(b);
  EXPECT_LT((factor.solve_leading(b) - expected).norm() / expected.norm(), 1e-10);
}

TEST(PartialCholesky, IndefiniteMatrixNamesTheColumnOfA) {
  // Identity but for one negative pivot, at the same index of A wherever it lands in the ordering.
  const Index n = 50, bad = 31;
  SparseMatrix A(n, n);
  A.setIdentity();
  A.coeffRef(bad, bad) = -1;
  A.makeCompressed();
  try {
    PartialCholesky factor(A, {3, 40});
    FAIL() << "expected NotPositiveDefinite";
  } catch (const NotPositiveDefinite& e) {
    EXPECT_EQ(e.column, bad);
  }
}

}  // namespace
}  // namespace roifem::solvers
