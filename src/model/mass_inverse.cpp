// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/mass_inverse.hpp"

#include <algorithm>
#include <vector>

#include "common/errors.hpp"

namespace roifem::model {

bool is_diagonal(const SparseMatrix& A) {
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() != it.col() && it.value() != 0) return false;
  return true;
}

MassInverse::MassInverse(const SparseMatrix& M) {
  if (model::is_diagonal(M)) {
    const Vector m = M.diagonal();
    if (!(m.size() == 0 || m.minCoeff() > 0)) throw ModelError("mass matrix: a non-positive diagonal entry");
    inverse_diagonal_ = m.cwiseInverse();
    return;
  }
  factor_ = std::make_unique<solvers::Cholesky>();
  try {
    factor_->compute(M);
  } catch (const solvers::NotPositiveDefinite& e) {
    throw ModelError(std::string("mass matrix is not positive definite: ") + e.what());
  }
}

void MassInverse::apply(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) const {
  if (factor_)
    factor_->solve(b, x);
  else
    x = inverse_diagonal_.cwiseProduct(b);
}

DenseMatrix MassInverse::apply(const DenseMatrix& B) const {
  return factor_ ? factor_->solve_matrix(B) : DenseMatrix(inverse_diagonal_.asDiagonal() * B);
}

SparseMatrix MassInverse::apply(const SparseMatrix& B) const {
  if (!factor_) return inverse_diagonal_.asDiagonal() * B;
  // Columns in chunks, each solved dense: memory stays at n x 256 whatever B's width. The factor of
  // a block-diagonal M is block diagonal, so the solve leaves exact zeros outside each column's
  // reach, and dropping them gives M^-1 B's own pattern.
  constexpr Index chunk = 256;
  std::vector<Eigen::Triplet<double>> entries;
  for (Index first = 0; first < B.cols(); first += chunk) {
    const Index width = std::min(chunk, B.cols() - first);
    const DenseMatrix X = factor_->solve_matrix(DenseMatrix(B.middleCols(first, width)));
    for (Index j = 0; j < width; ++j)
      for (Index i = 0; i < X.rows(); ++i)
        if (X(i, j) != 0) entries.emplace_back(i, first + j, X(i, j));
  }
  SparseMatrix result(B.rows(), B.cols());
  result.setFromTriplets(entries.begin(), entries.end());
  return result;
}

}  // namespace roifem::model
