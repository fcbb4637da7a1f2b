// SPDX-License-Identifier: GPL-3.0-or-later
// KLU's LU (solvers/sparse_lu.hpp) against Eigen's dense LU of the same unsymmetric matrix, its
// refactorization with new values, and its refusal of a singular matrix by column.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "solvers/sparse_lu.hpp"

namespace roifem::solvers {
namespace {

/// An unsymmetric, diagonally weighted random sparse matrix of size n (about 5 entries a row).
SparseMatrix unsymmetric_matrix(Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<Index> column(0, n - 1);
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 4 + value(rng));
    for (int k = 0; k < 4; ++k) entries.emplace_back(i, column(rng), value(rng));
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

TEST(SparseLu, SolvesAsDenseLuDoesAndRefactorsNewValues) {
  const Index n = 200;
  SparseMatrix A = unsymmetric_matrix(n, 1);
  ASSERT_GT((DenseMatrix(A) - DenseMatrix(A).transpose()).norm(), 1.0);
  const Vector b = Vector::LinSpaced(n, -1, 1);
  SparseLu lu;
  lu.analyze(A);
  Vector x(n);
  for (int round = 0; round < 2; ++round) {
    lu.factorize(A);
    lu.solve(b, x);
    const Vector expected = DenseMatrix(A).partialPivLu().solve(b);
    EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "round " << round;
    EXPECT_GT(lu.rcond(), 0);
    for (Index k = 0; k < A.nonZeros(); ++k) A.valuePtr()[k] *= 1 + 0.1 * std::sin(static_cast<double>(k));
  }
  EXPECT_EQ(lu.size(), n);
}

TEST(SparseLu, ASingularMatrixIsRefused) {
  SparseMatrix A = unsymmetric_matrix(20, 2);
  for (Index k = A.outerIndexPtr()[7]; k < A.outerIndexPtr()[8]; ++k) A.valuePtr()[k] = 0;  // column 7 zero
  SparseLu lu;
  try {
    lu.factorize(A);
    FAIL() << "no error";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roifem::solvers
