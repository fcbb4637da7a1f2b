// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/low_rank_update.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace roifem::solvers {

LowRankUpdate::LowRankUpdate(Solve solve_A, Index n)
    : solve_A_(std::move(solve_A)), n_(n), column_(static_cast<std::size_t>(n), -1), Z_(n, 0) {}

void LowRankUpdate::add(const std::vector<Index>& dofs, const DenseMatrix& B) {
  if (B.rows() != static_cast<Index>(dofs.size()) || B.cols() != B.rows())
    throw Error("internal: low-rank update: B is " + std::to_string(B.rows()) + " x " + std::to_string(B.cols()) + " for " +
                std::to_string(dofs.size()) + " dofs");
  std::vector<Index> at(dofs.size());  // each dof's column of U, new ones appended
  std::vector<Index> fresh;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const Index d = dofs[k];
    if (d < 0 || d >= n_) throw InputError("low-rank update: dof " + std::to_string(d) + " is not in the system");
    for (std::size_t j = 0; j < k; ++j)
      if (dofs[j] == d) throw InputError("low-rank update: dof " + std::to_string(d) + " is given twice");
    Index& column = column_[static_cast<std::size_t>(d)];
    if (column < 0) {
      column = static_cast<Index>(dofs_.size() + fresh.size());
      fresh.push_back(d);
    }
    at[k] = column;
  }
  // Z's new columns: A^-1 e_d, one solve each.
  const Index r_old = rank(), r = r_old + static_cast<Index>(fresh.size());
  Z_.conservativeResize(n_, r);
  Vector unit = Vector::Zero(n_), column(n_);
  for (std::size_t j = 0; j < fresh.size(); ++j) {
    unit[fresh[j]] = 1;
    solve_A_(unit, column);
    Z_.col(r_old + static_cast<Index>(j)) = column;
    unit[fresh[j]] = 0;
  }
  dofs_.insert(dofs_.end(), fresh.begin(), fresh.end());
  B_.conservativeResize(r, r);
  B_.bottomRows(r - r_old).setZero();
  B_.rightCols(r - r_old).setZero();
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j) B_(at[i], at[j]) += B(static_cast<Index>(i), static_cast<Index>(j));
  DenseMatrix UtZ(r, r);
  for (Index i = 0; i < r; ++i) UtZ.row(i) = Z_.row(dofs_[static_cast<std::size_t>(i)]);
  const DenseMatrix C = DenseMatrix::Identity(r, r) + B_ * UtZ;
  capacitance_.compute(C);
  // PartialPivLU does not report singularity: its reciprocal condition estimate does.
  if (!(capacitance_.rcond() > 1e-14))
    throw SolverError("low-rank update: the changed matrix is singular (capacitance condition estimate " +
                      std::to_string(capacitance_.rcond()) + ")");
  Ux_.resize(r);
  s_.resize(r);
  t_.resize(r);
}

void LowRankUpdate::solve(const Vector& b, Vector& x) const {
  solve_A_(b, x);
  if (dofs_.empty()) return;
  for (std::size_t i = 0; i < dofs_.size(); ++i) Ux_[static_cast<Index>(i)] = x[dofs_[i]];
  s_.noalias() = B_ * Ux_;
  t_ = capacitance_.solve(s_);
  x.noalias() -= Z_ * t_;
}

}  // namespace roifem::solvers
