// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// x = M^-1 b: by a product for the lumped (diagonal) mass of a full or statically condensed model,
/// by a Cholesky solve for the full mass blocks of a Guyan or Craig-Bampton reduction.
#include <memory>

#include "common/types.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::model {

class MassInverse {
 public:
  /// Throws ModelError when M is not positive definite.
  explicit MassInverse(const SparseMatrix& M);
  bool is_diagonal() const { return !factor_; }
  /// M^-1 as a vector; only for a diagonal M.
  const Vector& inverse_diagonal() const { return inverse_diagonal_; }
  void apply(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) const;
  /// M^-1 B for a dense block of right-hand sides.
  DenseMatrix apply(const DenseMatrix& B) const;
  /// M^-1 B as a sparse matrix, with the pattern M^-1 B truly has: a reduced model's M is diagonal
  /// but for a dense block on the interface and the modal coordinates (block diagonal), so M^-1 B
  /// is B's rows scaled outside the block and dense only in the block's rows (an implicit
  /// method's Jacobian -M^-1 K stays sparse). Exact zeros of the solve are left out.
  SparseMatrix apply(const SparseMatrix& B) const;

 private:
  Vector inverse_diagonal_;
  std::unique_ptr<solvers::Cholesky> factor_;
};

/// True when A has no non-zero off-diagonal entry.
bool is_diagonal(const SparseMatrix& A);

}  // namespace roifem::model
