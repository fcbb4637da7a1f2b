// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A sparse symmetric positive definite matrix A that one thread keeps changing by small symmetric
/// blocks (a cut's changes of K_eff) and solving with through Woodbury's correction of an older
/// factor (low_rank_update.hpp), factored afresh by a second thread, so that the correction's rank,
/// and with it every solve's O(n r) and every change's capacitance, stays small without the solving
/// thread ever waiting on a factorization (a haptic loop's tick cannot afford one: it takes some
/// 50 ticks on a 1,000-node ROI, docs/design-figures.md). It is the shape of asynchronous-preconditioner simulators.
///
/// The changes form a log: change i is A_{i+1} = A_i + U_i B_i U_i^T. Whenever the log has grown
/// since its last factor, the worker
///   1. copies A_k (its own copy of A with the log's first k changes added),
///   2. factors it (CHOLMOD, ordering and all: a split may add entries to the pattern),
///   3. solves A_k^-1 R for a fixed R given up front (the haptic tool's H^T: its compliance),
///   4. builds a correction on the new factor holding the changes logged since step 1 (their
///      columns A_k^-1 e_d, and those of the dofs the solving thread expects next, solved in one
///      multi-column solve; again while more were logged meanwhile),
/// and hands the result over (take()); the solving thread swaps it in between two of its steps in
/// O(1), adding by itself only the changes logged after step 4 (usually none). The old factor
/// goes back to the worker to be freed (retire()). A factor takes a change exactly as the
/// correction does, so the solutions are the same to round-off whichever factor a step uses.
///
/// The BLAS runs on one thread for the object's lifetime (OpenBLAS's count is per process): the
/// two threads each have a core of their own and the BLAS's threads would compete with both.
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "common/types.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/low_rank_update.hpp"

namespace roifem::solvers {

/// A symmetric change B (dofs.size() squared) on the rows and columns `dofs`.
struct SymmetricChange {
  std::vector<Index> dofs;
  DenseMatrix B;
};

/// A factor of A with the log's first `factored` changes, its correction holding the rest up to
/// `taken`, and the fixed right-hand sides' solutions with the factor.
struct RefreshedFactor {
  std::unique_ptr<Cholesky> factor;
  std::unique_ptr<LowRankUpdate> correction;  ///< on *factor; changes [factored, taken) of the log
  std::size_t factored = 0, taken = 0;
  DenseMatrix base_solution;  ///< A_factored^-1 R (the correction's correct() adds its changes)
  double seconds = 0;         ///< the worker's time for it, factorization to hand-over
};

/// Solves with A through the factor `factor` (owned elsewhere, at a fixed address): a correction
/// that takes its changes by Woodbury's identity, its columns in multi-column solves.
std::unique_ptr<LowRankUpdate> correction_on(Cholesky& factor);

class BackgroundRefactorization {
 public:
  /// A as it is now (compressed, symmetric), the dofs its factors order last (Cholesky::analyze),
  /// the fixed right-hand sides R (n x m). Starts the worker; it factors nothing until a change.
  BackgroundRefactorization(const SparseMatrix& A, std::vector<Index> last, DenseMatrix R);
  BackgroundRefactorization(const BackgroundRefactorization&) = delete;
  BackgroundRefactorization& operator=(const BackgroundRefactorization&) = delete;
  /// Stops the worker (a factorization under way runs to its end) and joins it.
  ~BackgroundRefactorization();

  /// Logs a change the solving thread has taken. Cheap: a copy of the change and a notification.
  void add(SymmetricChange change);
  /// The dofs the next changes will touch: each new factor comes with their columns (replaces the
  /// dofs given before). The worker makes a new factor for them even with no change logged (A as
  /// it is), so that a change is taken without a solve whenever its dofs were expected a
  /// factorization's time ahead.
  void expect(std::vector<Index> dofs);
  /// A new factor, when the worker has one ready (null otherwise; never waits). Rethrows, on this
  /// thread, what stopped the worker (a factorization that failed).
  std::unique_ptr<RefreshedFactor> take();
  /// The same, waiting until the worker has a factor with every change logged so far (null when
  /// none was logged since the last one taken): a known point, for tests and replays.
  std::unique_ptr<RefreshedFactor> take_current();
  /// A factor the solving thread no longer uses, with its correction, freed by the worker.
  void retire(std::unique_ptr<Cholesky> factor, std::unique_ptr<LowRankUpdate> correction);
  /// Changes [from, end) of the log (the solving thread's, after a factor it took: those it must add).
  std::vector<SymmetricChange> changes_since(std::size_t from) const;
  /// Factors the worker has made.
  long factorizations() const;

 private:
  void work();
  /// One factor of A with `k` changes, the later ones in its correction. Runs on the worker.
  std::unique_ptr<RefreshedFactor> refresh(std::size_t k);

  const BlasThreadsScope one_blas_thread_{1};
  // The worker's own: touched by it alone after construction.
  SparseMatrix A_;
  std::vector<Index> last_;
  DenseMatrix R_;
  std::size_t applied_ = 0;  ///< changes added to A_
  // Shared, under mutex_.
  mutable std::mutex mutex_;
  std::condition_variable wake_worker_, ready_;
  std::vector<SymmetricChange> log_;
  std::vector<Index> expected_;
  bool expected_changed_ = false;          ///< given since the last factor read them
  std::unique_ptr<RefreshedFactor> done_;  ///< ready, not yet taken
  std::size_t handed_ = 0;                 ///< changes in the last factor made (taken or not)
  /// Factors and corrections the solving thread gave back, to be freed by the worker.
  std::vector<std::pair<std::unique_ptr<Cholesky>, std::unique_ptr<LowRankUpdate>>> retired_;
  std::exception_ptr failure_;
  long factorizations_ = 0;
  bool stop_ = false;
  std::thread worker_;  ///< last: starts once everything above is made
};

}  // namespace roifem::solvers
