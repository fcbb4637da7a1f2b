// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/klu_solver.hpp"

#include <sunlinsol/sunlinsol_klu.h>

#include "common/timer.hpp"

namespace roifem::integrators::sundials {

KluSolver::KluSolver(N_Vector y, SUNMatrix A, SUNContext context, KluOrdering ordering) : klu_(SUNLinSol_KLU(y, A, context)) {
  if (!klu_) throw SolverError("SUNDIALS: cannot create the KLU linear solver");
  if (SUNLinSol_KLUSetOrdering(klu_.get(), static_cast<int>(ordering)) != 0)
    throw SolverError("SUNDIALS: KLU rejected the ordering");
  shell_ = SUNLinSolNewEmpty(context);
  if (!shell_) throw SolverError("SUNDIALS: cannot create a linear solver");
  shell_->content = this;
  shell_->ops->gettype = type;
  shell_->ops->initialize = initialize;
  shell_->ops->setup = setup;
  shell_->ops->solve = solve;
  shell_->ops->lastflag = last_flag;
  shell_->ops->free = free_shell;
}

KluSolver::~KluSolver() { SUNLinSolFreeEmpty(shell_); }

SUNLinearSolver_Type KluSolver::type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }

int KluSolver::initialize(SUNLinearSolver S) { return SUNLinSolInitialize(static_cast<KluSolver*>(S->content)->klu_.get()); }

int KluSolver::setup(SUNLinearSolver S, SUNMatrix A) {
  auto* me = static_cast<KluSolver*>(S->content);
  const Stopwatch clock;
  const int flag = SUNLinSolSetup(me->klu_.get(), A);
  const double seconds = clock.seconds();
  if (me->setups_++ == 0) me->first_setup_s_ = seconds;
  me->setup_s_ += seconds;
  return flag;
}

int KluSolver::solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol) {
  return SUNLinSolSolve(static_cast<KluSolver*>(S->content)->klu_.get(), A, x, b, tol);
}

sunindextype KluSolver::last_flag(SUNLinearSolver S) {
  return SUNLinSolLastFlag(static_cast<KluSolver*>(S->content)->klu_.get());
}

}  // namespace roifem::integrators::sundials
