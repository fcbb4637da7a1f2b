// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/background_refactorization.hpp"

#include <pthread.h>
#include <sched.h>

#include "common/errors.hpp"
#include "common/timer.hpp"

namespace roifem::solvers {

std::unique_ptr<LowRankUpdate> correction_on(Cholesky& factor) {
  return std::make_unique<LowRankUpdate>([&factor](const Vector& b, Vector& x) { factor.solve(b, x); }, factor.size(),
                                         [&factor](const DenseMatrix& columns) { return factor.solve_matrix(columns); });
}

BackgroundRefactorization::BackgroundRefactorization(const SparseMatrix& A, std::vector<Index> last, DenseMatrix R)
    : A_(A), last_(std::move(last)), R_(std::move(R)) {
  if (A_.rows() != A_.cols() || R_.rows() != A_.rows())
    throw Error("internal: background refactorization: A is " + std::to_string(A_.rows()) + " x " + std::to_string(A_.cols()) +
                ", R has " + std::to_string(R_.rows()) + " rows");
  A_.makeCompressed();
  worker_ = std::thread([this] { work(); });
}

BackgroundRefactorization::~BackgroundRefactorization() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_worker_.notify_one();
  worker_.join();
}

void BackgroundRefactorization::add(SymmetricChange change) {
  {
    const std::lock_guard lock(mutex_);
    log_.push_back(std::move(change));
  }
  wake_worker_.notify_one();
}

void BackgroundRefactorization::expect(std::vector<Index> dofs) {
  {
    const std::lock_guard lock(mutex_);
    expected_ = std::move(dofs);
    expected_changed_ = true;
  }
  wake_worker_.notify_one();
}

std::unique_ptr<RefreshedFactor> BackgroundRefactorization::take() {
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return nullptr;  // the worker is handing over or reading the log: next time
  if (failure_) std::rethrow_exception(failure_);
  if (!done_) return nullptr;
  std::unique_ptr<RefreshedFactor> fresh = std::move(done_);
  lock.unlock();
  wake_worker_.notify_one();
  return fresh;
}

std::unique_ptr<RefreshedFactor> BackgroundRefactorization::take_current() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (failure_) std::rethrow_exception(failure_);
    if (!done_ && handed_ == log_.size()) return nullptr;  // the last factor made holds every change and was taken
    ready_.wait(lock, [&] { return done_ != nullptr || failure_; });
    if (failure_) std::rethrow_exception(failure_);
    std::unique_ptr<RefreshedFactor> fresh = std::move(done_);
    if (fresh->taken == log_.size()) {
      lock.unlock();
      wake_worker_.notify_one();
      return fresh;
    }
    // Older than the log: dropped, the worker makes the next (freed without the lock held).
    lock.unlock();
    wake_worker_.notify_one();
    fresh.reset();
    lock.lock();
  }
}

void BackgroundRefactorization::retire(std::unique_ptr<Cholesky> factor, std::unique_ptr<LowRankUpdate> correction) {
  {
    const std::lock_guard lock(mutex_);
    retired_.emplace_back(std::move(factor), std::move(correction));
  }
  wake_worker_.notify_one();
}

std::vector<SymmetricChange> BackgroundRefactorization::changes_since(std::size_t from) const {
  const std::lock_guard lock(mutex_);
  if (from >= log_.size()) return {};
  return {log_.begin() + static_cast<std::ptrdiff_t>(from), log_.end()};
}

long BackgroundRefactorization::factorizations() const {
  const std::lock_guard lock(mutex_);
  return factorizations_;
}

void BackgroundRefactorization::work() {
#ifdef __linux__
  // The lowest class Linux has: whatever else wakes on this machine (the kernel's own work, other
  // programs) takes the worker's core first, not the solving thread's (the scheduler counts a core
  // that runs only SCHED_IDLE work as idle). A refusal leaves the worker as it was.
  const sched_param lowest{};
  pthread_setschedparam(pthread_self(), SCHED_IDLE, &lowest);
#endif
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_worker_.wait(lock,
                      [&] { return stop_ || !retired_.empty() || ((log_.size() > handed_ || expected_changed_) && !done_); });
    if (stop_) return;
    if (!retired_.empty()) {  // freed here, not on the solving thread, and without the lock held
      auto retired = std::move(retired_);
      retired_.clear();
      lock.unlock();
      retired.clear();
      lock.lock();
      continue;
    }
    const std::size_t k = log_.size();
    const std::vector<SymmetricChange> fresh(log_.begin() + static_cast<std::ptrdiff_t>(applied_), log_.end());
    lock.unlock();
    std::unique_ptr<RefreshedFactor> made;
    try {
      for (const SymmetricChange& change : fresh)
        for (std::size_t i = 0; i < change.dofs.size(); ++i)
          for (std::size_t j = 0; j < change.dofs.size(); ++j)  // inserts an entry a split's new coupling needs
            A_.coeffRef(change.dofs[i], change.dofs[j]) += change.B(static_cast<Index>(i), static_cast<Index>(j));
      if (!A_.isCompressed()) A_.makeCompressed();
      applied_ = k;
      made = refresh(k);
    } catch (...) {
      lock.lock();
      failure_ = std::current_exception();
      ready_.notify_all();
      return;
    }
    lock.lock();
    handed_ = made->taken;
    done_ = std::move(made);
    ++factorizations_;
    ready_.notify_all();
  }
}

std::unique_ptr<RefreshedFactor> BackgroundRefactorization::refresh(std::size_t k) {
  const Stopwatch clock;
  auto fresh = std::make_unique<RefreshedFactor>();
  fresh->factor = std::make_unique<Cholesky>();
  fresh->factor->compute(A_, last_);
  fresh->base_solution = fresh->factor->solve_matrix(R_);
  fresh->correction = correction_on(*fresh->factor);
  // The changes logged while it factored, and the dofs the next ones will touch: their columns in
  // one multi-column solve; the former then join the correction. Again for those logged meanwhile
  // (a few rounds at most: each is far shorter than the factorization).
  std::size_t taken = k;
  for (bool first = true;; first = false) {
    std::vector<SymmetricChange> later;
    std::vector<Index> wanted;
    {
      const std::lock_guard lock(mutex_);
      later.assign(log_.begin() + static_cast<std::ptrdiff_t>(taken), log_.end());
      if (first) {
        wanted = expected_;
        expected_changed_ = false;
      }
    }
    if (later.empty() && !first) break;
    for (const SymmetricChange& change : later) wanted.insert(wanted.end(), change.dofs.begin(), change.dofs.end());
    fresh->correction->prefetch(wanted);
    for (const SymmetricChange& change : later) fresh->correction->add(change.dofs, change.B);
    taken += later.size();
  }
  fresh->factored = k;
  fresh->taken = taken;
  fresh->seconds = clock.seconds();
  return fresh;
}

}  // namespace roifem::solvers
