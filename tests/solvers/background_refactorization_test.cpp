// SPDX-License-Identifier: GPL-3.0-or-later
// The background refactorization (solvers/background_refactorization.hpp): every factor the worker
// hands over, with the changes its correction holds, solves with the matrix that all the changes it
// says it holds make, against a dense factorization of that matrix assembled independently; the
// same while changes keep coming as it factors (those logged meanwhile land in the correction); a
// change that makes the matrix indefinite is reported on the solving thread.
#include "solvers/background_refactorization.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <iostream>
#include <random>

namespace roifem::solvers {
namespace {

/// A 2D five-point Laplacian on an m x m grid plus the identity: sparse, positive definite; its last
/// `dense` rows and columns also coupled to each other (a condensed model's interface block).
SparseMatrix grid_matrix(Index m, Index dense) {
  const Index n = m * m;
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < m; ++i)
    for (Index j = 0; j < m; ++j) {
      const Index k = i * m + j;
      entries.emplace_back(k, k, 5.0);
      if (i > 0) entries.emplace_back(k, k - m, -1.0);
      if (i + 1 < m) entries.emplace_back(k, k + m, -1.0);
      if (j > 0) entries.emplace_back(k, k - 1, -1.0);
      if (j + 1 < m) entries.emplace_back(k, k + 1, -1.0);
    }
  for (Index a = n - dense; a < n; ++a)
    for (Index b = n - dense; b < n; ++b)
      if (a != b) entries.emplace_back(a, b, 0.01);
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

std::vector<Index> last_rows(Index n, Index dense) {
  std::vector<Index> out;
  for (Index d = n - dense; d < n; ++d) out.push_back(d);
  return out;
}

/// A removal-like change on `dofs`: -S S^T / (4 r), small beside the diagonal so that A stays definite.
SymmetricChange random_change(std::vector<Index> dofs, std::mt19937& rng) {
  std::uniform_real_distribution<double> draw(-1, 1);
  const auto r = static_cast<Index>(dofs.size());
  DenseMatrix S(r, r);
  for (Index i = 0; i < r; ++i)
    for (Index j = 0; j < r; ++j) S(i, j) = draw(rng);
  return {std::move(dofs), -(S * S.transpose()) / (4.0 * static_cast<double>(r))};
}

void add_on(DenseMatrix& A, const SymmetricChange& change) {
  for (std::size_t i = 0; i < change.dofs.size(); ++i)
    for (std::size_t j = 0; j < change.dofs.size(); ++j)
      A(change.dofs[i], change.dofs[j]) += change.B(static_cast<Index>(i), static_cast<Index>(j));
}

/// The largest relative gap between what `fresh` solves (b and the fixed R) and a dense LLT of `A`.
double gap_to_dense(RefreshedFactor& fresh, const DenseMatrix& A, const DenseMatrix& R, const Vector& b) {
  const Eigen::LLT<DenseMatrix> dense(A);
  const Vector expected = dense.solve(b);
  Vector x(b.size());
  fresh.correction->solve(b, x);
  const DenseMatrix expected_R = dense.solve(R);
  DenseMatrix solution = fresh.base_solution;
  fresh.correction->correct(solution);
  return std::max((x - expected).norm() / expected.norm(), (solution - expected_R).norm() / expected_R.norm());
}

TEST(BackgroundRefactorization, EachFactorSolvesWithTheMatrixItsChangesMake) {
  std::mt19937 rng(7);
  const Index m = 12, n = m * m, dense = 20;
  const SparseMatrix A = grid_matrix(m, dense);
  DenseMatrix R = DenseMatrix::Zero(n, 3);
  R(5, 0) = R(77, 1) = R(n - 1, 2) = 1;
  std::vector<SymmetricChange> log;
  BackgroundRefactorization background(A, last_rows(n, dense), R);
  EXPECT_EQ(background.take_current(), nullptr);  // nothing changed: nothing to factor

  Vector b(n);
  std::uniform_real_distribution<double> draw(-1, 1);
  for (Index i = 0; i < n; ++i) b[i] = draw(rng);
  // One change, then two sharing dofs with it, the last coupling dofs 0 and 60, which A does not
  // (a split's new entry: the worker's copy of A grows its pattern and is analysed afresh).
  const std::vector<std::vector<std::vector<Index>>> rounds = {{{3, 15, 16, n - 2}}, {{15, 16, 40}, {0, 60, 3}}};
  for (const auto& round : rounds) {
    for (const auto& dofs : round) {
      log.push_back(random_change(dofs, rng));
      background.add(log.back());
    }
    const std::unique_ptr<RefreshedFactor> fresh = background.take_current();
    ASSERT_NE(fresh, nullptr);
    EXPECT_EQ(fresh->taken, log.size());
    DenseMatrix changed = A, factored = A;
    for (std::size_t i = 0; i < log.size(); ++i) {
      add_on(changed, log[i]);
      if (i < fresh->factored) add_on(factored, log[i]);
    }
    EXPECT_LT(gap_to_dense(*fresh, changed, R, b), 1e-13);
    // The factor alone is of A with the first `factored` changes.
    const DenseMatrix base = Eigen::LLT<DenseMatrix>(factored).solve(R);
    EXPECT_LT((fresh->base_solution - base).norm() / base.norm(), 1e-13);
    background.retire(std::move(fresh->factor), std::move(fresh->correction));
  }
  EXPECT_EQ(background.take_current(), nullptr);  // the last factor holds every change
  EXPECT_GE(background.factorizations(), 2);
}

TEST(BackgroundRefactorization, ChangesLoggedWhileItFactorsLandInTheCorrection) {
  // A solving thread that logs a change at every step and swaps in whatever factor is ready: each
  // one handed over solves with the matrix of the changes it holds (factored + corrected), however
  // the two threads interleave.
  std::mt19937 rng(11);
  const Index m = 40, n = m * m, dense = 60;
  const SparseMatrix A = grid_matrix(m, dense);
  DenseMatrix R = DenseMatrix::Zero(n, 2);
  R(100, 0) = R(n - 5, 1) = 1;
  std::vector<SymmetricChange> log;
  BackgroundRefactorization background(A, last_rows(n, dense), R);
  std::uniform_int_distribution<Index> dof(0, n - 1);
  Vector b = Vector::Ones(n);
  long checked = 0, with_later = 0;
  double worst = 0;
  const auto check = [&](std::unique_ptr<RefreshedFactor> fresh) {
    DenseMatrix changed = A;
    for (std::size_t i = 0; i < fresh->taken; ++i) add_on(changed, log[i]);
    worst = std::max(worst, gap_to_dense(*fresh, changed, R, b));
    ++checked;
    with_later += fresh->taken > fresh->factored ? 1 : 0;
    background.retire(std::move(fresh->factor), std::move(fresh->correction));
  };
  for (int step = 0; step < 60; ++step) {
    std::vector<Index> dofs;
    while (dofs.size() < 4) {
      const Index d = dof(rng);
      if (std::find(dofs.begin(), dofs.end(), d) == dofs.end()) dofs.push_back(d);
    }
    log.push_back(random_change(dofs, rng));
    background.add(log.back());
    background.expect({dof(rng), dof(rng)});
    if (auto fresh = background.take()) check(std::move(fresh));
  }
  if (auto fresh = background.take_current()) check(std::move(fresh));
  EXPECT_GE(checked, 1);
  EXPECT_LT(worst, 1e-12);
  std::cout << checked << " factors handed over, " << with_later << " with changes in their correction; largest gap " << worst
            << '\n';
}

TEST(BackgroundRefactorization, AChangeThatMakesTheMatrixIndefiniteIsReportedOnTheSolvingThread) {
  const Index m = 8, n = m * m;
  const SparseMatrix A = grid_matrix(m, 0);
  BackgroundRefactorization background(A, {}, DenseMatrix::Identity(n, 1));
  DenseMatrix B(1, 1);
  B(0, 0) = -10.0;  // the diagonal entry 5 becomes -5
  background.add({{9}, B});
  EXPECT_THROW(background.take_current(), NotPositiveDefinite);
  EXPECT_THROW(background.take(), NotPositiveDefinite);  // and stays reported
}

}  // namespace
}  // namespace roifem::solvers
