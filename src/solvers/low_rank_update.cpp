// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/low_rank_update.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace roifem::solvers {

LowRankUpdate::LowRankUpdate(Solve solve_A, Index n, SolveMany solve_many)
    : solve_A_(std::move(solve_A)),
      solve_many_(std::move(solve_many)),
      n_(n),
      column_(static_cast<std::size_t>(n), -1),
      Z_(n, 0) {}

namespace {

void check_dof(Index d, Index n) {
  if (d < 0 || d >= n) throw InputError("low-rank update: dof " + std::to_string(d) + " is not in the system");
}

}  // namespace

bool LowRankUpdate::has_column(Index d) const { return column_[static_cast<std::size_t>(d)] >= 0 || ahead_.count(d) > 0; }

void LowRankUpdate::prefetch(const std::vector<Index>& dofs) {
  std::vector<Index> wanted;
  for (const Index d : dofs) {
    check_dof(d, n_);
    if (!has_column(d) && std::find(wanted.begin(), wanted.end(), d) == wanted.end()) wanted.push_back(d);
  }
  if (wanted.empty()) return;
  DenseMatrix units = DenseMatrix::Zero(n_, static_cast<Index>(wanted.size()));
  for (std::size_t j = 0; j < wanted.size(); ++j) units(wanted[j], static_cast<Index>(j)) = 1;
  DenseMatrix columns(n_, static_cast<Index>(wanted.size()));
  if (solve_many_) {
    columns = solve_many_(units);
  } else {
    Vector column(n_);
    for (std::size_t j = 0; j < wanted.size(); ++j) {
      solve_A_(units.col(static_cast<Index>(j)), column);
      columns.col(static_cast<Index>(j)) = column;
    }
  }
  for (std::size_t j = 0; j < wanted.size(); ++j) ahead_.emplace(wanted[j], columns.col(static_cast<Index>(j)));
}

void LowRankUpdate::add(const std::vector<Index>& dofs, const DenseMatrix& B) {
  if (B.rows() != static_cast<Index>(dofs.size()) || B.cols() != B.rows())
    throw Error("internal: low-rank update: B is " + std::to_string(B.rows()) + " x " + std::to_string(B.cols()) + " for " +
                std::to_string(dofs.size()) + " dofs");
  // Everything is formed aside and kept only when it holds: a refused change leaves the update as it was.
  const Index r_old = rank();
  std::vector<Index> at(dofs.size());  // each dof's column of U, new ones appended
  std::vector<Index> fresh;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const Index d = dofs[k];
    check_dof(d, n_);
    for (std::size_t j = 0; j < k; ++j)
      if (dofs[j] == d) throw InputError("low-rank update: dof " + std::to_string(d) + " is given twice");
    const Index known = column_[static_cast<std::size_t>(d)];
    at[k] = known >= 0 ? known : r_old + static_cast<Index>(fresh.size());
    if (known < 0) fresh.push_back(d);
  }
  // Z's new columns: A^-1 e_d, prefetched or now, in one multi-column solve or one solve each, into
  // the room after Z's first r_old columns (grown by doubling; those columns stay as they are).
  const Index r = r_old + static_cast<Index>(fresh.size());
  if (Z_.cols() < r) {
    DenseMatrix grown(n_, std::max(r, 2 * Z_.cols()));
    grown.leftCols(r_old) = Z_.leftCols(r_old);
    Z_ = std::move(grown);
  }
  std::vector<std::size_t> to_solve;
  for (std::size_t j = 0; j < fresh.size(); ++j) {
    const auto ahead = ahead_.find(fresh[j]);
    if (ahead != ahead_.end())
      Z_.col(r_old + static_cast<Index>(j)) = ahead->second;
    else
      to_solve.push_back(j);
  }
  if (solve_many_ && !to_solve.empty()) {
    DenseMatrix units = DenseMatrix::Zero(n_, static_cast<Index>(to_solve.size()));
    for (std::size_t i = 0; i < to_solve.size(); ++i) units(fresh[to_solve[i]], static_cast<Index>(i)) = 1;
    const DenseMatrix solved = solve_many_(units);
    for (std::size_t i = 0; i < to_solve.size(); ++i)
      Z_.col(r_old + static_cast<Index>(to_solve[i])) = solved.col(static_cast<Index>(i));
  } else {
    Vector unit = Vector::Zero(n_), column(n_);
    for (const std::size_t j : to_solve) {
      unit[fresh[j]] = 1;
      solve_A_(unit, column);
      Z_.col(r_old + static_cast<Index>(j)) = column;
      unit[fresh[j]] = 0;
    }
  }
  DenseMatrix B_sum = DenseMatrix::Zero(r, r);
  std::vector<Index> all = dofs_;
  all.insert(all.end(), fresh.begin(), fresh.end());
  B_sum.topLeftCorner(r_old, r_old) = B_;
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j) B_sum(at[i], at[j]) += B(static_cast<Index>(i), static_cast<Index>(j));
  DenseMatrix UtZ(r, r);
  for (Index i = 0; i < r; ++i) UtZ.row(i) = Z_.row(all[static_cast<std::size_t>(i)]).head(r);
  Eigen::PartialPivLU<DenseMatrix> capacitance(DenseMatrix::Identity(r, r) + B_sum * UtZ);
  // PartialPivLU reports no singularity, and its rcond() estimate reads 1 for an exactly singular
  // matrix: the pivots tell.
  const Vector pivots = capacitance.matrixLU().diagonal().cwiseAbs();
  const double pivot_ratio = pivots.minCoeff() / pivots.maxCoeff();
  if (!(pivot_ratio > 1e-14))
    throw SolverError("low-rank update: the changed matrix is singular (the capacitance's pivots span a ratio of " +
                      std::to_string(pivot_ratio) + ")");
  for (std::size_t j = 0; j < fresh.size(); ++j) {
    column_[static_cast<std::size_t>(fresh[j])] = r_old + static_cast<Index>(j);
    ahead_.erase(fresh[j]);
  }
  dofs_ = std::move(all);
  B_ = std::move(B_sum);
  capacitance_ = std::move(capacitance);
  last_solved_ = static_cast<Index>(to_solve.size());
  Ux_.resize(r);
  s_.resize(r);
  t_.resize(r);
}

void LowRankUpdate::solve(const Vector& b, Vector& x) const {
  solve_A_(b, x);
  if (dofs_.empty()) return;
  coefficients(x, t_);
  subtract(t_, x);
}

void LowRankUpdate::coefficients(const Vector& x, Vector& c) const {
  for (std::size_t i = 0; i < dofs_.size(); ++i) Ux_[static_cast<Index>(i)] = x[dofs_[i]];
  s_.noalias() = B_ * Ux_;
  c = capacitance_.solve(s_);
}

DenseMatrix LowRankUpdate::coefficients(const DenseMatrix& X) const {
  DenseMatrix UtX(rank(), X.cols());
  for (std::size_t i = 0; i < dofs_.size(); ++i) UtX.row(static_cast<Index>(i)) = X.row(dofs_[i]);
  return capacitance_.solve(B_ * UtX);
}

void LowRankUpdate::subtract(const Vector& c, Vector& x) const { x.noalias() -= Z_.leftCols(rank()) * c; }

DenseMatrix LowRankUpdate::rows_of_Z(const std::vector<Index>& rows) const {
  DenseMatrix out(static_cast<Index>(rows.size()), rank());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Index>(i)) = Z_.row(rows[i]).head(rank());
  return out;
}

void LowRankUpdate::correct(DenseMatrix& X) const {
  if (dofs_.empty()) return;
  X.noalias() -= Z_.leftCols(rank()) * coefficients(X);
}

}  // namespace roifem::solvers
