// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// One Cholesky factorization that yields a Schur complement: for a symmetric positive definite
///   A = [[A_ll, A_lt], [A_tl, A_tt]]   (t: the "trailing" indices, l: the leading rest),
/// factor P A P^T = L L^T with the trailing indices ordered last, L = [[L_ll, 0], [L_tl, L_tt]].
/// Then
///   A_tt - A_tl A_ll^-1 A_lt = L_tt L_tt^T        (the trailing block of the factor, read off it),
///   A_ll^-1 b = P^T L^-T [I 0]^T [I 0] L^-1 P [b; 0]   (the leading block of the factor solves A_ll).
/// Static condensation needs exactly these two (A = K over the static dofs and the interface), and
/// gets them from one factorization instead of one solve per interface column. The leading indices
/// keep their places in CHOLMOD's own fill-reducing ordering of A (AMD or METIS); the trailing ones
/// follow in the order given. Supernodal, with BLAS.
#include <memory>
#include <vector>

#include "common/types.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::solvers {

class PartialCholesky {
 public:
  /// A: n x n symmetric (lower triangle read). trailing: distinct indices into A, in the order the
  /// Schur complement's rows take. Throws NotPositiveDefinite naming the column of A.
  PartialCholesky(const SparseMatrix& A, const std::vector<Index>& trailing);
  PartialCholesky(const PartialCholesky&) = delete;
  PartialCholesky& operator=(const PartialCholesky&) = delete;
  PartialCholesky(PartialCholesky&&) noexcept;
  PartialCholesky& operator=(PartialCholesky&&) noexcept;
  ~PartialCholesky();

  /// A_tt - A_tl A_ll^-1 A_lt (#t x #t, symmetric), rows and columns in the order of `trailing`.
  DenseMatrix trailing_schur_complement() const;
  /// x = A_ll^-1 b over the leading indices (A's indices not trailing, ascending).
  /// Non-const: the solve writes the object's CHOLMOD workspace (one thread at a time, as Cholesky).
  void solve_leading(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x);
  Vector solve_leading(const Eigen::Ref<const Vector>& b);
  /// The leading indices, ascending.
  const std::vector<Index>& leading() const;

  double factor_nonzeros() const;
  /// Seconds: ordering (analysis of A_ll and of A) and numeric factorization.
  double analysis_s() const;
  double factorization_s() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roifem::solvers
