// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/ida_solver.hpp"

#include <ida/ida.h>

#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/sundials/ida_support.hpp"

namespace roifem::integrators::sundials {

IdaSolver::IdaSolver(Settings settings, Residual residual, const SparseMatrix& dF_dy, const SparseMatrix& dF_dyp)
    : settings_(std::move(settings)), residual_(std::move(residual)), dF_dy_(dF_dy), dF_dyp_(dF_dyp), context_(make_context()) {
  if (dF_dy.nonZeros() != dF_dyp.nonZeros())
    throw Error("internal: " + settings_.name + ": the Jacobian's two parts differ in pattern");
  const Index n = dF_dy.rows();
  y_ = make_vector(n, context_.get());
  yp_ = make_vector(n, context_.get());
  y().setZero();
  yp().setZero();
}

IdaSolver::~IdaSolver() {
  memory_.reset();  // before the solver and the vectors it refers to
  solver_.reset();
}

void IdaSolver::check(int flag, const char* call) const {
  if (flag < 0)
    throw SolverError(settings_.name + ": " + call + " failed: " + flag_name(IDAGetReturnFlagName(flag)) + last_error_.detail());
}

int IdaSolver::residual_callback(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<IdaSolver*>(self);
  // A Newton iterate may be inadmissible (an element inverted) where the step's answer is not: IDA
  // may retry it smaller.
  const int flag = guarded_recoverable_callback(
      me->pending_, me->inadmissible_, -1, [&] { me->residual_(t, view(y), view(yp), view(r)); }, t);
  if (flag != 1 || ++me->refused_ < max_refused_per_output) return flag;
  long steps = 0;
  IDAGetNumSteps(me->memory_.get(), &steps);
  me->pending_ = std::make_exception_ptr(SolverError(
      me->settings_.name + ": step " + std::to_string(me->before_.steps + steps + 1) + ", t = " + number_text(t) +
      " s: " + std::to_string(max_refused_per_output) +
      " Newton iterates in this output interval inverted an element, each retried at a smaller step (the solution presses "
      "on an inversion; a smaller load or motion, or a finer mesh there); the last: " +
      me->inadmissible_));
  return -1;
}

int IdaSolver::jacobian_callback(double t, double c_j, N_Vector y, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector,
                                 N_Vector, N_Vector) {
  auto* me = static_cast<IdaSolver*>(self);
  return guarded_callback(
      me->pending_, -1,
      [&] {
        if (me->settings_.update_dF_dy) {
          me->settings_.update_dF_dy(t, view(y));
          if (me->dF_dy_.nonZeros() != me->dF_dyp_.nonZeros())
            throw Error("internal: " + me->settings_.name + ": the updated dF/dy left the Newton matrix's pattern");
        }
        write_newton_matrix(me->dF_dy_, me->dF_dyp_, c_j, J);
      },
      t);
}

void IdaSolver::start(double t0) {
  pending_ = nullptr;
  inadmissible_.clear();
  if (memory_) {  // a restart: the same memory, linear solver and pattern
    before_ = stats();
    before_.factorization_s = 0;
    check(IDAReInit(memory_.get(), t0, y_.get(), yp_.get()), "IDAReInit");
    return;
  }
  memory_.reset(IDACreate(context_.get()));
  if (!memory_) throw SolverError(settings_.name + ": IDACreate failed");
  check(IDAInit(memory_.get(), residual_callback, t0, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(memory_.get(), this), "IDASetUserData");
  check(IDASetErrHandlerFn(memory_.get(), LastError::handler, &last_error_), "IDASetErrHandlerFn");
  check(IDASStolerances(memory_.get(), settings_.rtol, settings_.atol), "IDASStolerances");
  check(IDASetMaxOrd(memory_.get(), settings_.max_order), "IDASetMaxOrd");
  check(IDASetMaxNumSteps(memory_.get(), settings_.max_steps), "IDASetMaxNumSteps");
  if (settings_.differential) {
    id_ = make_vector(settings_.differential->size(), context_.get());
    view(id_.get()) = *settings_.differential;
    check(IDASetId(memory_.get(), id_.get()), "IDASetId");
    if (settings_.suppress_algebraic) check(IDASetSuppressAlg(memory_.get(), SUNTRUE), "IDASetSuppressAlg");
  }
  J_ = make_sparse(dF_dy_, context_.get());
  solver_ = std::make_unique<KluSolver>(y_.get(), J_.get(), context_.get());
  check(IDASetLinearSolver(memory_.get(), solver_->get(), J_.get()), "IDASetLinearSolver");
  check(IDASetJacFn(memory_.get(), jacobian_callback), "IDASetJacFn");
}

void IdaSolver::make_consistent(double t_first) {
  refused_ = 0;
  const int flag = IDACalcIC(memory_.get(), IDA_YA_YDP_INIT, t_first);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  check(flag, "IDACalcIC");
  check(IDAGetConsistentIC(memory_.get(), y_.get(), yp_.get()), "IDAGetConsistentIC");
}

double IdaSolver::advance_to(double t_out) {
  if (!memory_) throw Error("internal: " + settings_.name + ": advance_to before start");
  IDASetStopTime(memory_.get(), t_out);
  refused_ = 0;
  double t_reached = t_out;
  const int flag = IDASolve(memory_.get(), t_out, &t_reached, y_.get(), yp_.get(), IDA_NORMAL);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  if (flag < 0) {
    long steps = 0;
    IDAGetNumSteps(memory_.get(), &steps);
    throw SolverError(settings_.name + ": failed at t = " + number_text(t_reached) + " s (step " +
                      std::to_string(before_.steps + steps) + "): " + flag_name(IDAGetReturnFlagName(flag)) +
                      last_error_.detail() +
                      (inadmissible_.empty() ? "" : "; the last Newton iterate rejected: " + inadmissible_));
  }
  return t_reached;
}

Stats IdaSolver::current() const { return ida_stats(memory_.get()); }

Stats IdaSolver::stats() const {
  Stats s = current();
  s.steps += before_.steps;
  s.rhs_evals += before_.rhs_evals;
  s.jac_evals += before_.jac_evals;
  s.lin_setups += before_.lin_setups;
  s.lin_solves += before_.lin_solves;
  s.failed_steps += before_.failed_steps;
  if (solver_) s.factorization_s = solver_->setup_seconds();
  return s;
}

}  // namespace roifem::integrators::sundials
