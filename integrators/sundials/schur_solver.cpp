// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/schur_solver.hpp"

#include <cmath>

#include "common/timer.hpp"

namespace roifem::integrators::sundials {

namespace {
SUNLinearSolver_Type direct_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
int free_shell(SUNLinearSolver) { return 0; }  // the owner (SchurSolver) frees it
}  // namespace

SchurSolver::SchurSolver(SUNContext context, const model::SecondOrderSystem& system, bool mass_form)
    : system_(system), mass_form_(mass_form) {
  solver_ = SUNLinSolNewEmpty(context);
  if (!solver_) throw SolverError("SUNDIALS: cannot create a linear solver");
  solver_->content = this;
  solver_->ops->gettype = direct_type;
  solver_->ops->setup = setup;
  solver_->ops->solve = solve;
  solver_->ops->free = free_shell;
  rhs_.resize(system.size());
  work_.resize(system.size());
}

SchurSolver::~SchurSolver() { SUNLinSolFreeEmpty(solver_); }

int SchurSolver::setup(SUNLinearSolver S, SUNMatrix A) {
  auto* me = static_cast<SchurSolver*>(S->content);
  try {
    // gamma = -A(0, n): find row 0 in column n of the CSC matrix.
    const sunindextype n = static_cast<sunindextype>(me->system_.size());
    const sunindextype* col = SUNSparseMatrix_IndexPointers(A);
    const sunindextype* row = SUNSparseMatrix_IndexValues(A);
    const double* value = SUNSparseMatrix_Data(A);
    double gamma = NAN;
    for (sunindextype k = col[n]; k < col[n + 1]; ++k)
      if (row[k] == 0) gamma = -value[k];
    if (!(gamma > 0)) return -1;  // unrecoverable: not the matrix this solver was built for
    if (gamma != me->gamma_) {
      const Stopwatch clock;
      const SparseMatrix Smat = me->system_.M + gamma * me->system_.C + (gamma * gamma) * me->system_.K;
      if (me->factorizations_ == 0) me->schur_.analyze(Smat);
      me->schur_.factorize(Smat);
      me->gamma_ = gamma;
      ++me->factorizations_;
      me->factorization_s_ += clock.seconds();
    }
    return 0;
  } catch (...) {
    return -1;
  }
}

int SchurSolver::solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double) {
  auto* me = static_cast<SchurSolver*>(S->content);
  const Index n = me->system_.size();
  const auto B = view(b);
  auto X = view(x);
  const double gamma = me->gamma_;
  // rhs = gamma (M b_v or b_v) + (M + gamma C) b_u
  if (me->mass_form_)
    me->rhs_ = gamma * B.tail(n);
  else
    me->rhs_.noalias() = gamma * (me->system_.M * B.tail(n));
  me->rhs_.noalias() += me->system_.M * B.head(n);
  me->rhs_.noalias() += gamma * (me->system_.C * B.head(n));
  me->schur_.solve(me->rhs_, me->work_);
  X.tail(n) = (me->work_ - B.head(n)) / gamma;
  X.head(n) = me->work_;
  return 0;
}

}  // namespace roifem::integrators::sundials
