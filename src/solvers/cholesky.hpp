// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Sparse Cholesky factorization A = L L^T of a symmetric positive definite matrix, by CHOLMOD
/// (supernodal where it pays, with BLAS; simplicial otherwise). RAII over cholmod_common and
/// the factor; the pattern is analysed once (fill-reducing ordering) and re-factorized as values
/// change; solves reuse CHOLMOD's workspace (cholmod_solve2), so a time step allocates nothing.
/// A reads as symmetric from its lower triangle; full symmetric storage is fine.
///
/// Threads: every call into CHOLMOD, solves included, writes the object's cholmod_common (status,
/// statistics) and its solve workspace, so those methods are non-const and an object serves one
/// thread at a time. Threads that solve concurrently each hold their own factor.
#include <memory>
#include <vector>

#include "common/types.hpp"

namespace roifem::solvers {

class Cholesky {
 public:
  enum class Kind { automatic, simplicial, supernodal };
  explicit Cholesky(Kind kind = Kind::automatic);
  Cholesky(const Cholesky&) = delete;
  Cholesky& operator=(const Cholesky&) = delete;
  Cholesky(Cholesky&&) noexcept;
  Cholesky& operator=(Cholesky&&) noexcept;
  ~Cholesky();

  /// Symbolic analysis: ordering and the factor's pattern.
  void analyze(const SparseMatrix& A);
  /// The same with the indices `last` ordered after all others (CHOLMOD's constrained AMD, CAMD):
  /// for a matrix with a dense block (a condensed K_eff's interface), whose dofs then form one
  /// trailing dense supernode instead of pieces an unconstrained ordering may scatter.
  void analyze(const SparseMatrix& A, const std::vector<Index>& last);
  /// Numeric factorization (analyze first, or it is done here). Throws NotPositiveDefinite.
  void factorize(const SparseMatrix& A);
  /// analyze + factorize.
  void compute(const SparseMatrix& A) {
    analyze(A);
    factorize(A);
  }
  void compute(const SparseMatrix& A, const std::vector<Index>& last) {
    analyze(A, last);
    factorize(A);
  }

  Vector solve(const Eigen::Ref<const Vector>& b);
  /// x = A^-1 b into x (no allocation after the first call of the same size).
  void solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x);
  DenseMatrix solve_matrix(const Eigen::Ref<const DenseMatrix>& B);

  Index size() const;
  /// The fill-reducing ordering: the k-th column of L is column ordering()[k] of A.
  std::vector<Index> ordering() const;
  /// Non-zeros in L.
  double factor_nonzeros() const;
  /// CHOLMOD's reciprocal condition estimate (min/max of diag(L))^2.
  double rcond();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Thrown when A is not (numerically) positive definite; `column` is the column where the
/// factorization stopped (-1 when it finished but the reciprocal condition number is ~ 0).
class NotPositiveDefinite : public std::runtime_error {
 public:
  NotPositiveDefinite(Index column, double rcond);
  Index column;
  double rcond;
};

}  // namespace roifem::solvers
