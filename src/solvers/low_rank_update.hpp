// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Solves with a matrix that a low-rank change has made from one already factored, without a new
/// factorization (Woodbury's identity, in its push-through form, which needs no inverse of B):
///   (A + U B U^T)^-1 b = x - Z (I + B U^T Z)^-1 B U^T x,   x = A^-1 b,   Z = A^-1 U,
/// where U selects r rows (the dofs a change touches) and B is r x r. A cut that removes
/// tetrahedra changes the trapezoidal rule's K_eff so (fem/element_removal.hpp): each element a
/// 12 x 12 block on its dofs. Z costs one solve with A's factor per dof, once per change (all of a
/// change's columns in one multi-column solve where one is given: BLAS-3 in a supernodal factor);
/// a solve then costs one with A's factor and O(n r) more. Changes accumulate: U is the union of their
/// dofs, B the sum of their blocks. Z's columns A^-1 e_d do not depend on the changes, so they can
/// be computed ahead (prefetch()), between a haptic loop's ticks or before a blade reaches the
/// dofs; a change whose columns are all ahead costs no solve, only the r x r capacitance.
#include <Eigen/LU>
#include <functional>
#include <unordered_map>
#include <vector>

#include "common/types.hpp"

namespace roifem::solvers {

class LowRankUpdate {
 public:
  /// x = A^-1 b with the factor of A (n x n) kept; x does not alias b.
  using Solve = std::function<void(const Vector& b, Vector& x)>;
  /// X = A^-1 B for several columns at once.
  using SolveMany = std::function<DenseMatrix(const DenseMatrix& B)>;
  LowRankUpdate(Solve solve_A, Index n, SolveMany solve_many = {});

  /// Adds B (symmetric, dofs.size() squared) on the rows and columns `dofs` (distinct, in
  /// [0, n)). Throws InputError for a dof out of range or given twice, SolverError when
  /// A + U B U^T is singular (the capacitance I + B U^T Z is).
  void add(const std::vector<Index>& dofs, const DenseMatrix& B);
  /// x = (A + U B U^T)^-1 b; x does not alias b.
  void solve(const Vector& b, Vector& x) const;
  /// X = A^-1 R for some R, in place: becomes (A + U B U^T)^-1 R (no solve with A's factor).
  void correct(DenseMatrix& X) const;
  /// The correction in its parts, for a caller that combines it with others (the haptic loop's
  /// constraint): for x = A^-1 b, (A + U B U^T)^-1 b = x - Z c with c = (I + B U^T Z)^-1 B U^T x.
  /// c (r) for x; C = the same for the columns of X (r x X.cols()): O(r^2) per column.
  void coefficients(const Vector& x, Vector& c) const;
  DenseMatrix coefficients(const DenseMatrix& X) const;
  /// x -= Z c: O(n r).
  void subtract(const Vector& c, Vector& x) const;
  /// Z's rows `rows` (rows.size() x r).
  DenseMatrix rows_of_Z(const std::vector<Index>& rows) const;
  /// Computes A^-1 e_d for the dofs given (those not yet in U nor computed), for later add()s.
  /// InputError for a dof out of range.
  void prefetch(const std::vector<Index>& dofs);
  /// Whether A^-1 e_d is at hand for dof d (in U already, or prefetched).
  bool has_column(Index d) const;
  /// Columns the last add() solved (those not ahead).
  Index last_solved() const { return last_solved_; }
  /// r: the dofs the changes touch.
  Index rank() const { return static_cast<Index>(dofs_.size()); }
  const std::vector<Index>& dofs() const { return dofs_; }

 private:
  Solve solve_A_;
  SolveMany solve_many_;
  Index n_;
  std::vector<Index> dofs_;                       ///< U's rows, in the order they came
  std::vector<Index> column_;                     ///< per dof of A, its column of U, or -1
  DenseMatrix B_;                                 ///< r x r
  DenseMatrix Z_;                                 ///< n x capacity, its first r columns Z (room to grow without copying it)
  std::unordered_map<Index, Vector> ahead_;       ///< prefetched columns A^-1 e_d
  Eigen::PartialPivLU<DenseMatrix> capacitance_;  ///< I + B U^T Z
  mutable Vector Ux_, s_, t_;                     ///< solve()'s work, sized by add()
  Index last_solved_ = 0;
};

}  // namespace roifem::solvers
