// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule's one linear solve per step: x = K_eff^-1 (f + M w), with
///   K_eff = K + 2/dt C + 4/dt^2 M     (C = alpha M: K + c M, c = 4/dt^2 + 2 alpha/dt),
/// w the history term the rule builds from u, v and a (trapezoid.hpp). Three strategies:
///   DirectSolve      CHOLMOD factor of K_eff, the dense blocks' dofs ordered last ("trapezoid")
///   ConjugateGradients  Jacobi-preconditioned CG, no factor ("trapezoid-cg")
///   ModalElimination a system's declared modal coordinates eliminated in closed form first
///                    (modal_elimination.hpp), chosen by "trapezoid" when the system has them
#include <memory>

#include "model/average_acceleration.hpp"
#include "model/second_order_system.hpp"
#include "solvers/background_refactorization.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/jacobi_cg.hpp"
#include "solvers/low_rank_update.hpp"

namespace roifem::integrators {

class EffectiveStiffnessSolver {
 public:
  virtual ~EffectiveStiffnessSolver() = default;
  /// x = K_eff^-1 (f + M w). x must not alias f or w; where uses_initial_guess(), x holds one on entry.
  virtual void solve(const Vector& f, const Vector& w, Vector& x) = 0;
  virtual bool uses_initial_guess() const { return false; }
  /// Iterations of the last solves, summed (iterative strategies).
  virtual long iterations() const { return 0; }
  /// K_eff has changed by B on the rows and columns `dofs` (the system with it): takes it without a
  /// new factorization where the strategy can (returns true), or returns false (the caller re-prepares).
  virtual bool update(const std::vector<Index>& /*dofs*/, const DenseMatrix& /*B*/) { return false; }
};

/// When DirectSolve takes a change by Woodbury's correction and when it asks for a new factor.
enum class Refactor {
  /// Once the accumulated correction would cost a solve more than the factor's own solve does
  /// (2 n r + 2 r^2 flops against 4 nnz(L): the steps after it at more than twice a plain step's
  /// cost), update() returns false and the caller factors the changed K_eff afresh.
  when_costlier,
  never,  ///< always the correction (the haptic loop, which must not stall a tick on a factorization)
};

class DirectSolve final : public EffectiveStiffnessSolver {
 public:
  /// Throws solvers::NotPositiveDefinite.
  DirectSolve(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
              Refactor refactor = Refactor::when_costlier);
  void solve(const Vector& f, const Vector& w, Vector& x) override;
  /// x = K_eff^-1 (f + M w) with the factored K_eff, without the changes taken since (correction()
  /// adds them: x - Z c).
  void solve_base(const Vector& f, const Vector& w, Vector& x);
  /// By Woodbury's identity on the factor it holds (solvers/low_rank_update.hpp); changes
  /// accumulate, until the policy asks for a new factor (returns false, taking nothing).
  bool update(const std::vector<Index>& dofs, const DenseMatrix& B) override;
  /// The changes taken so far (null before any): corrects solutions with the factored K_eff.
  const solvers::LowRankUpdate* correction() const { return changed_.get(); }
  /// Solves ahead for the dofs a coming change will touch (solvers::LowRankUpdate::prefetch), so
  /// that update() then costs no solve for them.
  void prefetch(const std::vector<Index>& dofs);
  /// Takes a factor made elsewhere (a background refactorization) of K_eff with some of the changes
  /// taken so far, and a correction on it holding the others: the same K_eff, held anew. Returns
  /// the factor and correction it held (to be freed where a free costs no tick).
  std::pair<std::unique_ptr<solvers::Cholesky>, std::unique_ptr<solvers::LowRankUpdate>> adopt(
      std::unique_ptr<solvers::Cholesky> factor, std::unique_ptr<solvers::LowRankUpdate> correction);

 private:
  const model::SecondOrderSystem& system_;
  std::unique_ptr<solvers::Cholesky> K_eff_;  ///< at a fixed address: the correction solves with it
  Refactor refactor_;
  std::unique_ptr<solvers::LowRankUpdate> changed_;  ///< made at the first update or prefetch
  Vector rhs_;
  solvers::LowRankUpdate& changes();
  const Vector& right_hand_side(const Vector& f, const Vector& w);  ///< f + M w, in rhs_
};

class ConjugateGradients final : public EffectiveStiffnessSolver {
 public:
  ConjugateGradients(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
                     solvers::CgSettings settings);
  void solve(const Vector& f, const Vector& w, Vector& x) override;
  bool uses_initial_guess() const override { return true; }
  long iterations() const override { return iterations_; }

 private:
  const model::SecondOrderSystem& system_;
  solvers::JacobiCg cg_;
  Vector rhs_;
  long iterations_ = 0;
};

}  // namespace roifem::integrators
