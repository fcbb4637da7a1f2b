#include "integrators/ida.hpp"

#include <ida/ida.h>

#include <cmath>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/sundials/ida_support.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_ida(const IntegratorInfo& info, const StepControl& control) {
  return std::make_unique<Ida>(info.name, info.method_id, control);
}

Ida::Ida(std::string name, int max_order, StepControl control)
    : name_(std::move(name)), max_order_(max_order), control_(control), context_(sundials::make_context()) {
  if (!(control_.rtol > 0 && control_.atol > 0)) throw InputError(name_ + ": tolerances rtol and atol must be positive");
}

int Ida::residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<Ida*>(self);
  return guarded_callback(me->pending_, -1, [&] {
    const Index n = me->system_->size();
    const auto Y = sundials::view(y), YP = sundials::view(yp);
    auto R = sundials::view(r);
    me->system_->load.evaluate(t, me->force_);
    R.head(n) = YP.head(n) - Y.tail(n);
    me->system_->apply_stiffness(Y.head(n), R.tail(n));
    R.tail(n).noalias() += me->system_->M * YP.tail(n) + me->system_->C * Y.tail(n) - me->force_;
  });
}

int Ida::jacobian(double, double c_j, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Ida*>(self);
  return guarded_callback(me->pending_, -1, [&] { sundials::write_newton_matrix(me->dF_dy_, me->dF_dyp_, c_j, J); });
}

void Ida::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  const Index n = system.size();
  force_.resize(n);
  memory_.reset();  // before the solver and vectors it refers to
  solver_.reset();
  J_.reset();
  pending_ = nullptr;
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
  const std::vector<Index> sizes{n, n};
  const SparseMatrix dyp = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}});
  dF_dy_ = assemble_blocks(sizes, {{0, 1, &I, -1.0}, {1, 0, &system.K}, {1, 1, &system.C}}, &dyp);
  dF_dyp_ = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}}, &dF_dy_);
  if (dF_dy_.nonZeros() != dF_dyp_.nonZeros()) throw Error("internal: IDA Jacobian patterns differ");

  // Consistent initial values: y' = [v; M^-1 (f - C v - K u)].
  y_ = sundials::make_vector(2 * n, context_.get());
  yp_ = sundials::make_vector(2 * n, context_.get());
  auto y = sundials::view(y_.get()), yp = sundials::view(yp_.get());
  y.head(n) = initial.u;
  y.tail(n) = initial.v;
  solvers::Cholesky mass;
  mass.compute(system.M);
  yp.head(n) = initial.v;
  yp.tail(n) = mass.solve(system.load.at(initial.t) - system.C * initial.v - system.K * initial.u);

  memory_.reset(IDACreate(context_.get()));
  if (!memory_) throw SolverError(name_ + ": IDACreate failed");
  auto check = [&](int flag, const char* call) {
    if (flag < 0) throw SolverError(name_ + ": " + call + " failed: " + sundials::flag_name(IDAGetReturnFlagName(flag)));
  };
  check(IDAInit(memory_.get(), residual, initial.t, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(memory_.get(), this), "IDASetUserData");
  check(IDASetErrHandlerFn(memory_.get(), sundials::LastError::handler, &last_error_), "IDASetErrHandlerFn");
  check(IDASStolerances(memory_.get(), control_.rtol, control_.atol), "IDASStolerances");
  check(IDASetMaxOrd(memory_.get(), max_order_), "IDASetMaxOrd");
  check(IDASetMaxNumSteps(memory_.get(), 1000000), "IDASetMaxNumSteps");
  J_ = sundials::make_sparse(dF_dy_, context_.get());
  solver_ = std::make_unique<sundials::KluSolver>(y_.get(), J_.get(), context_.get());
  check(IDASetLinearSolver(memory_.get(), solver_->get(), J_.get()), "IDASetLinearSolver");
  check(IDASetJacFn(memory_.get(), jacobian), "IDASetJacFn");
}

void Ida::advance(double t_out, model::State& state) {
  IDASetStopTime(memory_.get(), t_out);
  double t_reached = state.t;
  const int flag = IDASolve(memory_.get(), t_out, &t_reached, y_.get(), yp_.get(), IDA_NORMAL);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  long steps = 0;
  IDAGetNumSteps(memory_.get(), &steps);
  if (flag < 0)
    throw SolverError(name_ + ": failed at t = " + number_text(t_reached) + " s (step " + std::to_string(steps) +
                      "): " + sundials::flag_name(IDAGetReturnFlagName(flag)) + last_error_.detail());
  const Index n = system_->size();
  const auto y = sundials::view(y_.get());
  state.t = t_reached;
  state.u = y.head(n);
  state.v = y.tail(n);
}

Stats Ida::stats() const {
  Stats s = sundials::ida_stats(memory_.get());
  if (solver_) s.factorization_s = solver_->setup_seconds();
  return s;
}

}  // namespace roifem::integrators
