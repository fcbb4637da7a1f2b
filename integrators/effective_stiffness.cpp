// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/effective_stiffness.hpp"

#include <algorithm>

namespace roifem::integrators {

DirectSolve::DirectSolve(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule, Refactor refactor)
    : system_(system), refactor_(refactor), rhs_(system.size()) {
  K_eff_.compute(rule.effective_stiffness(system), system.dense_block_dofs());
}

void DirectSolve::solve(const Vector& f, const Vector& w, Vector& x) {
  system_.apply_mass(w, rhs_);
  rhs_ += f;
  if (changed_)
    changed_->solve(rhs_, x);
  else
    K_eff_.solve(rhs_, x);
}

solvers::LowRankUpdate& DirectSolve::changes() {
  if (!changed_)
    changed_ =
        std::make_unique<solvers::LowRankUpdate>([this](const Vector& b, Vector& x) { K_eff_.solve(b, x); }, system_.size(),
                                                 [this](const DenseMatrix& columns) { return K_eff_.solve_matrix(columns); });
  return *changed_;
}

bool DirectSolve::update(const std::vector<Index>& dofs, const DenseMatrix& B) {
  if (refactor_ == Refactor::when_costlier) {
    auto r = static_cast<double>(changes().rank());
    for (const Index d : dofs)
      if (std::find(changes().dofs().begin(), changes().dofs().end(), d) == changes().dofs().end()) ++r;
    const auto n = static_cast<double>(system_.size());
    if (2 * n * r + 2 * r * r > 4 * K_eff_.factor_nonzeros()) return false;
  }
  changes().add(dofs, B);
  return true;
}

void DirectSolve::prefetch(const std::vector<Index>& dofs) { changes().prefetch(dofs); }

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
