// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Sparse LU factorization of a general (unsymmetric) square matrix by SuiteSparse's KLU: the
/// ordering (AMD on A + A^T, block triangular form) analysed once for a pattern, then a numeric
/// factorization with partial pivoting per call, and in-place solves. RAII over klu_common, the
/// symbolic and the numeric objects; one object serves one thread at a time. For the Jacobians
/// that are not symmetric (integrators/energy_momentum.hpp's); Cholesky (solvers/cholesky.hpp)
/// where they are.
#include <memory>

#include "common/types.hpp"

namespace roifem::solvers {

class SparseLu {
 public:
  SparseLu();
  SparseLu(const SparseLu&) = delete;
  SparseLu& operator=(const SparseLu&) = delete;
  SparseLu(SparseLu&&) noexcept;
  SparseLu& operator=(SparseLu&&) noexcept;
  ~SparseLu();

  /// Symbolic analysis of A's pattern (A compressed, column-major).
  void analyze(const SparseMatrix& A);
  /// Numeric factorization (analyze first, or it is done here). Throws SolverError when A is
  /// singular to working precision, naming the column.
  void factorize(const SparseMatrix& A);
  /// x = A^-1 b into x.
  void solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x);
  Index size() const;
  /// KLU's cheap reciprocal condition estimate, min |U_ii| / max |U_ii|.
  double rcond();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roifem::solvers
