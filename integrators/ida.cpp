#include "integrators/ida.hpp"

#include <ida/ida.h>
#include <sunlinsol/sunlinsol_klu.h>

#include <cmath>
#include <utility>

#include "common/errors.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::integrators {

namespace {
/// [[A, B], [C, D]] for n x n blocks, with every entry of `pattern_of` present (explicit zeros),
/// so that two such matrices share one pattern.
SparseMatrix blocks(Index n, const SparseMatrix& A, const SparseMatrix& B, const SparseMatrix& C, const SparseMatrix& D,
                    const SparseMatrix* pattern_of = nullptr) {
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&](const SparseMatrix& X, Index r0, Index c0, double scale) {
    for (Index j = 0; j < X.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(X, j); it; ++it) t.emplace_back(r0 + it.row(), c0 + it.col(), scale * it.value());
  };
  add(A, 0, 0, 1);
  add(B, 0, n, 1);
  add(C, n, 0, 1);
  add(D, n, n, 1);
  if (pattern_of) add(*pattern_of, 0, 0, 0.0);
  SparseMatrix out(2 * n, 2 * n);
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}
}  // namespace

Ida::Ida(std::string name, int max_order, StepControl control)
    : name_(std::move(name)), max_order_(max_order), control_(control), context_(sundials::make_context()) {
  if (!(control_.rtol > 0 && control_.atol > 0)) throw InputError(name_ + ": tolerances rtol and atol must be positive");
}

Ida::~Ida() {
  if (memory_) IDAFree(&memory_);
}

int Ida::residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<Ida*>(self);
  try {
    const Index n = me->system_->size();
    const auto Y = sundials::view(y), YP = sundials::view(yp);
    auto R = sundials::view(r);
    me->system_->load.evaluate(t, me->force_);
    R.head(n) = YP.head(n) - Y.tail(n);
    me->system_->apply_stiffness(Y.head(n), R.tail(n));
    R.tail(n).noalias() += me->system_->M * YP.tail(n) + me->system_->C * Y.tail(n) - me->force_;
    return 0;
  } catch (...) {
    me->pending_ = std::current_exception();
    return -1;
  }
}

int Ida::jacobian(double, double c_j, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Ida*>(self);
  try {
    SparseMatrix newton = me->dF_dy_;
    newton.coeffs() += c_j * me->dF_dyp_.coeffs();  // same pattern by construction
    sundials::copy_into(newton, J);
    return 0;
  } catch (...) {
    me->pending_ = std::current_exception();
    return -1;
  }
}

void Ida::reset(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  const Index n = system.size();
  force_.resize(n);
  if (memory_) IDAFree(&memory_);
  solver_.reset();
  J_.reset();
  pending_ = nullptr;
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n)), Z(n, n);
  const SparseMatrix dyp = blocks(n, I, Z, Z, system.M);
  dF_dy_ = blocks(n, Z, -I, system.K, system.C, &dyp);
  dF_dyp_ = blocks(n, I, Z, Z, system.M, &dF_dy_);
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

  memory_ = IDACreate(context_.get());
  if (!memory_) throw SolverError(name_ + ": IDACreate failed");
  auto check = [&](int flag, const char* call) {
    if (flag < 0) throw SolverError(name_ + ": " + call + " failed: " + IDAGetReturnFlagName(flag));
  };
  check(IDAInit(memory_, residual, initial.t, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(memory_, this), "IDASetUserData");
  check(IDASStolerances(memory_, control_.rtol, control_.atol), "IDASStolerances");
  check(IDASetMaxOrd(memory_, max_order_), "IDASetMaxOrd");
  check(IDASetMaxNumSteps(memory_, 1000000), "IDASetMaxNumSteps");
  J_ = sundials::make_sparse(dF_dy_, context_.get());
  solver_.reset(SUNLinSol_KLU(y_.get(), J_.get(), context_.get()));
  if (!solver_) throw SolverError(name_ + ": cannot create the KLU solver");
  SUNLinSol_KLUSetOrdering(solver_.get(), 0);  // AMD
  check(IDASetLinearSolver(memory_, solver_.get(), J_.get()), "IDASetLinearSolver");
  check(IDASetJacFn(memory_, jacobian), "IDASetJacFn");
}

void Ida::advance_to(double t_out, model::State& state) {
  if (!memory_) throw Error("internal: " + name_ + ": advance_to before reset");
  IDASetStopTime(memory_, t_out);
  double t_reached = state.t;
  const int flag = IDASolve(memory_, t_out, &t_reached, y_.get(), yp_.get(), IDA_NORMAL);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  long steps = 0;
  IDAGetNumSteps(memory_, &steps);
  if (flag < 0)
    throw SolverError(name_ + ": failed at t = " + std::to_string(t_reached) + " s (step " + std::to_string(steps) +
                      "): " + IDAGetReturnFlagName(flag));
  const Index n = system_->size();
  const auto y = sundials::view(y_.get());
  if (!y.allFinite()) throw SolverError(name_ + ": non-finite solution at t = " + std::to_string(t_reached) + " s");
  state.t = t_reached;
  state.u = y.head(n);
  state.v = y.tail(n);
}

Stats Ida::stats() const {
  Stats s;
  if (!memory_) return s;
  IDAGetNumSteps(memory_, &s.steps);
  IDAGetNumResEvals(memory_, &s.rhs_evals);
  IDAGetNumJacEvals(memory_, &s.jac_evals);
  IDAGetNumLinSolvSetups(memory_, &s.lin_setups);
  IDAGetNumNonlinSolvIters(memory_, &s.lin_solves);
  IDAGetNumErrTestFails(memory_, &s.failed_steps);
  return s;
}

}  // namespace roifem::integrators
