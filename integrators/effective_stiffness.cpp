// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/effective_stiffness.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace roifem::integrators {

DirectSolve::DirectSolve(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule, Refactor refactor)
    : system_(system), K_eff_(std::make_unique<solvers::Cholesky>()), refactor_(refactor), rhs_(system.size()) {
  K_eff_->compute(rule.effective_stiffness(system), system.dense_block_dofs());
}

void DirectSolve::solve(const Vector& f, const Vector& w, Vector& x) {
  if (changed_)
    changed_->solve(right_hand_side(f, w), x);
  else
    K_eff_->solve(right_hand_side(f, w), x);
}

void DirectSolve::solve_base(const Vector& f, const Vector& w, Vector& x) { K_eff_->solve(right_hand_side(f, w), x); }

const Vector& DirectSolve::right_hand_side(const Vector& f, const Vector& w) {
  system_.apply_mass(w, rhs_);
  rhs_ += f;
  return rhs_;
}

solvers::LowRankUpdate& DirectSolve::changes() {
  if (!changed_) changed_ = solvers::correction_on(*K_eff_);
  return *changed_;
}

bool DirectSolve::update(const std::vector<Index>& dofs, const DenseMatrix& B) {
  if (refactor_ == Refactor::when_costlier) {
    auto r = static_cast<double>(changes().rank());
    for (const Index d : dofs)
      if (std::find(changes().dofs().begin(), changes().dofs().end(), d) == changes().dofs().end()) ++r;
    const auto n = static_cast<double>(system_.size());
    if (2 * n * r + 2 * r * r > 4 * K_eff_->factor_nonzeros()) return false;
  }
  changes().add(dofs, B);
  return true;
}

void DirectSolve::prefetch(const std::vector<Index>& dofs) { changes().prefetch(dofs); }

std::pair<std::unique_ptr<solvers::Cholesky>, std::unique_ptr<solvers::LowRankUpdate>> DirectSolve::adopt(
    std::unique_ptr<solvers::Cholesky> factor, std::unique_ptr<solvers::LowRankUpdate> correction) {
  if (!factor || factor->size() != system_.size()) throw Error("internal: DirectSolve::adopt: a factor of another size");
  std::pair held{std::move(K_eff_), std::move(changed_)};
  K_eff_ = std::move(factor);
  changed_ = std::move(correction);
  return held;
}

ConjugateGradients::ConjugateGradients(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
                                       solvers::CgSettings settings)
    : system_(system), cg_(settings), rhs_(system.size()) {
  cg_.compute(rule.effective_stiffness(system));
}

void ConjugateGradients::solve(const Vector& f, const Vector& w, Vector& x) {
  system_.apply_mass(w, rhs_);
  rhs_ += f;
  iterations_ += cg_.solve(rhs_, x);
}

}  // namespace roifem::integrators
