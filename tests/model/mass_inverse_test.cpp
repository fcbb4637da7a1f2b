// SPDX-License-Identifier: GPL-3.0-or-later
// M^-1 B for a sparse B against the dense inverse, and its pattern against the one a block-diagonal
// M implies: B's own pattern in the diagonal rows, the block's rows dense over the columns B's
// block rows reach.
#include "model/mass_inverse.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace roifem::model {
namespace {

TEST(MassInverse, SparseProductOfABlockDiagonalMassHasThePatternItImpliesAndTheDenseValues) {
  // M: diagonal but for a dense SPD block on {2, 5, 7} (as a reduced model's interface and modes).
  constexpr Index n = 10;
  const std::vector<Index> block{2, 5, 7};
  DenseMatrix M_dense = DenseMatrix::Zero(n, n);
  for (Index i = 0; i < n; ++i) M_dense(i, i) = 1.0 + 0.1 * static_cast<double>(i);
  for (Index a : block)
    for (Index b : block) M_dense(a, b) += (a == b ? 2.0 : 0.3);
  const SparseMatrix M = M_dense.sparseView();
  // B: a tridiagonal band.
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < n; ++i)
    for (Index j = std::max<Index>(0, i - 1); j <= std::min<Index>(n - 1, i + 1); ++j)
      t.emplace_back(i, j, 1.0 + static_cast<double>(i + 2 * j));
  SparseMatrix B(n, n);
  B.setFromTriplets(t.begin(), t.end());

  const SparseMatrix X = MassInverse(M).apply(B);
  const DenseMatrix expected = M_dense.inverse() * DenseMatrix(B);
  EXPECT_LT((DenseMatrix(X) - expected).norm() / expected.norm(), 1e-14);
  // Pattern: a block row holds every column any block row of B holds; any other row is B's row.
  std::vector<bool> reached(n, false), in_block(n, false);
  for (Index a : block) in_block[static_cast<std::size_t>(a)] = true;
  for (Index a : block)
    for (Index j = 0; j < n; ++j)
      if (B.coeff(a, j) != 0) reached[static_cast<std::size_t>(j)] = true;
  Index expected_nonzeros = 0;
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) {
      const bool nonzero = in_block[static_cast<std::size_t>(i)] ? reached[static_cast<std::size_t>(j)] : B.coeff(i, j) != 0;
      expected_nonzeros += nonzero;
      EXPECT_EQ(X.coeff(i, j) != 0, nonzero) << "entry (" << i << ", " << j << ")";
    }
  EXPECT_EQ(X.nonZeros(), expected_nonzeros);
  EXPECT_LT(expected_nonzeros, n * n / 2);  // sparse: the point of the pattern
}

TEST(MassInverse, SparseProductOfALumpedMassScalesTheRows) {
  const Vector m = Vector::LinSpaced(4, 1.0, 4.0);
  const SparseMatrix M = DenseMatrix(m.asDiagonal()).sparseView();
  const SparseMatrix B = DenseMatrix::Constant(4, 4, 2.0).sparseView();
  const SparseMatrix X = MassInverse(M).apply(B);
  EXPECT_LT((DenseMatrix(X) - m.cwiseInverse().asDiagonal() * DenseMatrix(B)).norm(), 1e-15);
}

}  // namespace
}  // namespace roifem::model
