#include "integrators/arkode.hpp"

#include <arkode/arkode_arkstep.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::integrators {

namespace {

}  // namespace

Arkode::Arkode(ArkodeMethod method, StepControl control)
    : method_(std::move(method)), control_(control), context_(sundials::make_context()) {
  if (!(control_.dt > 0) || !std::isfinite(control_.dt))
    throw InputError(method_.name + ": time step dt = " + std::to_string(control_.dt) + " s must be positive");
  if (control_.adaptive && !(control_.rtol > 0 && control_.atol > 0))
    throw InputError(method_.name + ": tolerances rtol and atol must be positive");
}

Arkode::~Arkode() {
  if (memory_) ARKStepFree(&memory_);
}

void Arkode::check(int flag, const char* call, double t) const {
  if (flag < 0)
    throw SolverError(method_.name + ": " + call + " failed at t = " + number_text(t) + " s: " +
                      sundials::flag_name(ARKStepGetReturnFlagName(flag)));
}

void Arkode::evaluate_rhs(double t, const double* y, double* ydot) {
  const Index n = system_->size();
  const Eigen::Map<const Vector> u(y, n), v(y + n, n);
  Eigen::Map<Vector> du(ydot, n), dv(ydot + n, n);
  system_->load.evaluate(t, force_);
  // K u is the costly part; a stage often evaluates f at the u of the previous evaluation (the
  // Newton residual at the trivial predictor, see reset), so K u is kept keyed by u's exact values.
  if (!(cached_u_.size() == n && std::memcmp(cached_u_.data(), y, sizeof(double) * static_cast<std::size_t>(n)) == 0)) {
    cached_u_ = u;
    system_->apply_stiffness(u, cached_Ku_);
  }
  work_ = force_ - cached_Ku_;
  work_.noalias() -= system_->C * v;
  du = v;
  if (method_.mass_matrix)
    dv = work_;
  else
    mass_inverse_->apply(work_, dv);
}

int Arkode::rhs(double t, N_Vector y, N_Vector ydot, void* self) {
  auto* me = static_cast<Arkode*>(self);
  try {
    me->evaluate_rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    return 0;
  } catch (...) {
    me->pending_ = std::current_exception();
    return -1;
  }
}

int Arkode::unit_weights(N_Vector, N_Vector ewt, void*) {
  N_VConst(1.0, ewt);
  return 0;
}

int Arkode::jacobian(double, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Arkode*>(self);
  sundials::copy_into(me->jacobian_, J);  // constant: the problem is linear
  return 0;
}

int Arkode::mass(double, SUNMatrix M, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Arkode*>(self);
  sundials::copy_into(me->mass_matrix_, M);
  return 0;
}

void Arkode::reset(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  const Index n = system.size();
  mass_inverse_.reset();
  if (!method_.mass_matrix) mass_inverse_ = std::make_unique<model::MassInverse>(system.M);
  force_.resize(n);
  work_.resize(n);
  cached_u_.resize(0);
  cached_Ku_.resize(n);
  if (memory_) ARKStepFree(&memory_);
  solver_.reset();
  mass_solver_.reset();
  schur_.reset();
  J_.reset();
  M_.reset();
  pending_ = nullptr;

  y_ = sundials::make_vector(2 * n, context_.get());
  auto y = sundials::view(y_.get());
  y.head(n) = initial.u;
  y.tail(n) = initial.v;
  memory_ = method_.implicit ? ARKStepCreate(nullptr, rhs, initial.t, y_.get(), context_.get())
                             : ARKStepCreate(rhs, nullptr, initial.t, y_.get(), context_.get());
  if (!memory_) throw SolverError(method_.name + ": ARKStepCreate failed");
  check(ARKStepSetUserData(memory_, this), "ARKStepSetUserData", initial.t);
  check(ARKStepSetErrHandlerFn(memory_, sundials::LastError::handler, &last_error_), "ARKStepSetErrHandlerFn", initial.t);
  check(ARKStepSetMaxNumSteps(memory_, 1000000), "ARKStepSetMaxNumSteps", initial.t);
  if (control_.adaptive) {
    check(ARKStepSStolerances(memory_, control_.rtol, control_.atol), "ARKStepSStolerances", initial.t);
    check(ARKStepSetInitStep(memory_, control_.dt), "ARKStepSetInitStep", initial.t);
  } else {
    check(ARKStepSetFixedStep(memory_, control_.dt), "ARKStepSetFixedStep", initial.t);
    // At a fixed step the error weights steer nothing (no error test, and a linear problem's one
    // Newton iteration skips the convergence test): unit weights, set in one pass instead of the
    // five of ARKODE's tolerance-based weights at every step.
    check(ARKStepWFtolerances(memory_, unit_weights), "ARKStepWFtolerances", initial.t);
  }
  // Lagrange interpolation keeps past solutions only; Hermite would also keep f at every step.
  check(ARKStepSetInterpolantType(memory_, ARK_INTERP_LAGRANGE), "ARKStepSetInterpolantType", initial.t);

  if (method_.trapezoid) {
    double c[2] = {0.0, 1.0}, A[4] = {0.0, 0.0, 0.5, 0.5}, b[2] = {0.5, 0.5};
    ARKodeButcherTable table = ARKodeButcherTable_Create(2, 2, 0, c, A, b, nullptr);
    const int flag = ARKStepSetTables(memory_, 2, 0, table, nullptr);
    ARKodeButcherTable_Free(table);
    check(flag, "ARKStepSetTables", initial.t);
  } else if (method_.implicit) {
    check(ARKStepSetTableNum(memory_, static_cast<ARKODE_DIRKTableID>(method_.table), ARKODE_ERK_NONE),
          "ARKStepSetTableNum", initial.t);
  } else {
    check(ARKStepSetTableNum(memory_, ARKODE_DIRK_NONE, static_cast<ARKODE_ERKTableID>(method_.table)),
          "ARKStepSetTableNum", initial.t);
  }

  if (method_.implicit) {
    const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
    if (method_.mass_matrix) {
      jacobian_ = assemble_blocks({n, n}, {{0, 1, &I}, {1, 0, &system.K, -1.0}, {1, 1, &system.C, -1.0}});
      mass_matrix_ = assemble_blocks({n, n}, {{0, 0, &I}, {1, 1, &system.M}});
      M_ = sundials::make_sparse(mass_matrix_, context_.get());
      mass_solver_ = std::make_unique<sundials::KluSolver>(y_.get(), M_.get(), context_.get(), method_.klu_ordering);
      check(ARKStepSetMassLinearSolver(memory_, mass_solver_->get(), M_.get(), SUNFALSE), "ARKStepSetMassLinearSolver",
            initial.t);
      check(ARKStepSetMassFn(memory_, mass), "ARKStepSetMassFn", initial.t);
    } else if (method_.schur) {
      // The Schur solver reads only gamma from the Newton matrix (its top-right block, -gamma I).
      jacobian_ = assemble_blocks({n, n}, {{0, 1, &I}});
    } else {
      // Sparse for a lumped M, and for a reduced model's block-diagonal one too (dense only in the
      // interface and modal rows; see MassInverse::apply).
      const SparseMatrix MinvK = mass_inverse_->apply(system.K), MinvC = mass_inverse_->apply(system.C);
      jacobian_ = assemble_blocks({n, n}, {{0, 1, &I}, {1, 0, &MinvK, -1.0}, {1, 1, &MinvC, -1.0}});
    }
    J_ = sundials::make_sparse(jacobian_, context_.get());
    SUNLinearSolver linear_solver = nullptr;
    if (method_.schur) {
      schur_ = std::make_unique<sundials::SchurSolver>(context_.get(), system, method_.mass_matrix);
      linear_solver = schur_->get();
    } else {
      solver_ = std::make_unique<sundials::KluSolver>(y_.get(), J_.get(), context_.get(), method_.klu_ordering);
      linear_solver = solver_->get();
    }
    check(ARKStepSetLinearSolver(memory_, linear_solver, J_.get()), "ARKStepSetLinearSolver", initial.t);
    check(ARKStepSetJacFn(memory_, jacobian), "ARKStepSetJacFn", initial.t);
    check(ARKStepSetLinear(memory_, 0), "ARKStepSetLinear", initial.t);  // linear, constant Jacobian
    // f_i at each stage follows from the stage solution (z - predictor) / (h a_ii): saves one
    // right-hand side (a K product) per implicit stage.
    check(ARKStepSetDeduceImplicitRhs(memory_, SUNTRUE), "ARKStepSetDeduceImplicitRhs", initial.t);
    // The one Newton iteration of a linear problem is exact from any initial guess, so the guess
    // may as well be the trivial predictor z = y_n: its residual needs f(t_stage, y_n), whose K u_n
    // the cache above already holds from the stage before.
    check(ARKStepSetPredictorMethod(memory_, 0), "ARKStepSetPredictorMethod", initial.t);
    // Refactor only when gamma = h a_ii changes (never at a fixed step of an SDIRK/ESDIRK table).
    check(ARKStepSetLSetupFrequency(memory_, INT_MAX / 2), "ARKStepSetLSetupFrequency", initial.t);
    if (!control_.adaptive) check(ARKStepSetDeltaGammaMax(memory_, 1e-8), "ARKStepSetDeltaGammaMax", initial.t);
  }
}

void Arkode::advance_to(double t_out, model::State& state) {
  if (!memory_) throw Error("internal: " + method_.name + ": advance_to before reset");
  check(ARKStepSetStopTime(memory_, t_out), "ARKStepSetStopTime", state.t);
  double t_reached = state.t;
  const int flag = ARKStepEvolve(memory_, t_out, y_.get(), &t_reached, ARK_NORMAL);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  long steps = 0;
  ARKStepGetNumSteps(memory_, &steps);
  // At a fixed step the error weights are 1 (see reset), so ARKODE's "too much accuracy" test
  // (eps ||y|| > 1) is what a diverging solution trips first: report it as the divergence it is.
  if (flag == ARK_TOO_MUCH_ACC && !control_.adaptive)
    throw SolverError(method_.name + ": the solution diverged (|y| > 1/eps) by t = " + number_text(t_reached) + " s, step " +
                      std::to_string(steps) + "; the step is beyond the method's stability limit");
  if (flag < 0)
    throw SolverError(method_.name + ": failed at t = " + number_text(t_reached) + " s (step " + std::to_string(steps) +
                      "): " + sundials::flag_name(ARKStepGetReturnFlagName(flag)) + last_error_.detail());
  const Index n = system_->size();
  const auto y = sundials::view(y_.get());
  if (!y.allFinite())
    throw SolverError(method_.name + ": the solution diverged (non-finite values) by t = " + number_text(t_reached) +
                      " s, step " + std::to_string(steps) + "; the step is beyond the method's stability limit");
  state.t = t_reached;
  state.u = y.head(n);
  state.v = y.tail(n);
}

Stats Arkode::stats() const {
  Stats s;
  if (!memory_) return s;
  long nfe = 0, nfi = 0, attempts = 0, value = 0;
  ARKStepGetNumSteps(memory_, &s.steps);
  ARKStepGetNumRhsEvals(memory_, &nfe, &nfi);
  s.rhs_evals = nfe + nfi;
  ARKStepGetNumStepAttempts(memory_, &attempts);
  s.failed_steps = attempts - s.steps;
  if (method_.implicit) {
    ARKStepGetNumJacEvals(memory_, &s.jac_evals);
    ARKStepGetNumLinSolvSetups(memory_, &s.lin_setups);
    ARKStepGetNumNonlinSolvIters(memory_, &value);  // one linear solve per Newton iteration
    s.lin_solves = value;
  }
  if (solver_) s.factorization_s += solver_->setup_seconds();
  if (mass_solver_) s.factorization_s += mass_solver_->setup_seconds();
  if (schur_) s.factorization_s += schur_->factorization_seconds();
  return s;
}

}  // namespace roifem::integrators
