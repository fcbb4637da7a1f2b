// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/arkode.hpp"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/integrator_table.hpp"
#include "model/time_grid.hpp"

namespace roifem::integrators {

Arkode::Arkode(ArkodeMethod method, StepControl control)
    : method_(std::move(method)), control_(control), context_(sundials::make_context()) {
  model::check_time_step(control_.dt, method_.name);
  if (control_.adaptive && !(control_.rtol > 0 && control_.atol > 0))
    throw InputError(method_.name + ": tolerances rtol and atol must be positive");
}

ArkodeMethod arkode_method(const IntegratorInfo& info) {
  if (info.family != Family::arkode) throw InputError("integrator '" + info.name + "' is not an ARKODE method");
  const bool mass = info.linear_solver == LinearSolver::klu_mass || info.linear_solver == LinearSolver::schur_mass;
  const bool schur = info.linear_solver == LinearSolver::schur || info.linear_solver == LinearSolver::schur_mass;
  return {.name = info.name,
          .implicit = !info.is_explicit,
          .table = info.method_id,
          .trapezoid = !info.is_explicit && info.method_id < 0,
          .mass_matrix = mass,
          .schur = schur,
          .order = info.order,
          .klu_ordering = sundials::KluOrdering::amd};
}

ArkodeMethod arkode_method(const std::string& name) { return arkode_method(integrator_info(name)); }

std::unique_ptr<Integrator> make_arkode(const IntegratorInfo& info, const StepControl& control) {
  return std::make_unique<Arkode>(arkode_method(info), control);
}

void Arkode::check(int flag, const char* call) const {
  if (flag < 0)
    throw SolverError(method_.name + ": " + call + " failed at t = " + number_text(t0_) +
                      " s: " + sundials::flag_name(ARKStepGetReturnFlagName(flag)));
}

int Arkode::rhs(double t, N_Vector y, N_Vector ydot, void* self) {
  auto* me = static_cast<Arkode*>(self);
  const auto evaluate = [&] { me->form_->evaluate(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot)); };
  // An implicit method's Newton iterate may be inadmissible (an element inverted) where the step's
  // answer is not: ARKODE may retry it smaller.
  return me->method_.implicit ? guarded_recoverable_callback(me->pending_, me->inadmissible_, -1, evaluate, t)
                              : guarded_callback(me->pending_, -1, evaluate, t);
}

int Arkode::unit_weights(N_Vector, N_Vector ewt, void*) {
  N_VConst(1.0, ewt);
  return 0;
}

int Arkode::jacobian(double t, N_Vector y, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Arkode*>(self);
  return guarded_callback(
      me->pending_, -1,
      [&] {
        // A linear problem's Jacobian is constant; a nonlinear one's holds the tangent at y's u, on
        // the first Jacobian's pattern, so that KLU refactors on its one symbolic analysis.
        if (me->system_->is_nonlinear())
          me->jacobian_ = me->newton_jacobian(me->form_->stiffness(t, N_VGetArrayPointer(y)), &me->jacobian_pattern_);
        sundials::copy_into(me->jacobian_, J);
      },
      t);
}

SparseMatrix Arkode::newton_jacobian(const SparseMatrix& K, const SparseMatrix* pattern_of) const {
  const Index n = system_->size();
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
  if (method_.mass_matrix) return assemble_blocks({n, n}, {{0, 1, &I}, {1, 0, &K, -1.0}, {1, 1, &system_->C, -1.0}}, pattern_of);
  if (method_.schur)  // the Schur solver reads only gamma from the Newton matrix (its top-right block, -gamma I)
    return assemble_blocks({n, n}, {{0, 1, &I}}, pattern_of);
  // Sparse for a lumped M, and for a reduced model's block-diagonal one too (dense only in the
  // interface and modal rows; see MassInverse::apply).
  const SparseMatrix minus_MinvK = form_->lower_left(K), minus_MinvC = form_->lower_right();
  return assemble_blocks({n, n}, {{0, 1, &I}, {1, 0, &minus_MinvK}, {1, 1, &minus_MinvC}}, pattern_of);
}

int Arkode::mass(double, SUNMatrix M, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<Arkode*>(self);
  sundials::copy_into(me->mass_matrix_, M);
  return 0;
}

void Arkode::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  t0_ = initial.t;
  memory_.reset();  // before the solvers and vectors it refers to
  solver_.reset();
  mass_solver_.reset();
  schur_.reset();
  J_.reset();
  M_.reset();
  pending_ = nullptr;
  inadmissible_.clear();
  form_ =
      std::make_unique<FirstOrderForm>(system, method_.mass_matrix ? FirstOrderForm::Mass::kept : FirstOrderForm::Mass::inverted);
  create_memory(initial);
  set_steps();
  set_butcher_table();
  if (method_.implicit) attach_linear_solvers();
}

void Arkode::create_memory(const model::State& initial) {
  const Index n = system_->size();
  y_ = sundials::make_vector(2 * n, context_.get());
  auto y = sundials::view(y_.get());
  y.head(n) = initial.u;
  y.tail(n) = initial.v;
  memory_.reset(method_.implicit ? ARKStepCreate(nullptr, rhs, initial.t, y_.get(), context_.get())
                                 : ARKStepCreate(rhs, nullptr, initial.t, y_.get(), context_.get()));
  if (!memory_) throw SolverError(method_.name + ": ARKStepCreate failed");
  check(ARKStepSetUserData(memory_.get(), this), "ARKStepSetUserData");
  check(ARKStepSetErrHandlerFn(memory_.get(), sundials::LastError::handler, &last_error_), "ARKStepSetErrHandlerFn");
  check(ARKStepSetMaxNumSteps(memory_.get(), 1000000), "ARKStepSetMaxNumSteps");
}

void Arkode::set_steps() {
  if (control_.adaptive) {
    check(ARKStepSStolerances(memory_.get(), control_.rtol, control_.atol), "ARKStepSStolerances");
    // An explicit method's first trial step of dt can take a nonlinear model's stages far past
    // the stability limit, where an element inverts before the error test can shrink it (ARKODE
    // 6.4 cannot retry an explicit stage): there ARKODE estimates its own first step (0).
    const bool own_first_step = !method_.implicit && system_->is_nonlinear();
    check(ARKStepSetInitStep(memory_.get(), own_first_step ? 0.0 : control_.dt), "ARKStepSetInitStep");
  } else {
    check(ARKStepSetFixedStep(memory_.get(), control_.dt), "ARKStepSetFixedStep");
    if (method_.implicit && system_->is_nonlinear()) {
      // The weights are Newton's convergence test: rtol and atol, as with adaptive steps.
      check(ARKStepSStolerances(memory_.get(), control_.rtol, control_.atol), "ARKStepSStolerances");
    } else {
      // At a fixed step the error weights steer nothing (no error test, and a linear problem's one
      // Newton iteration skips the convergence test): unit weights, set in one pass instead of the
      // five of ARKODE's tolerance-based weights at every step.
      check(ARKStepWFtolerances(memory_.get(), unit_weights), "ARKStepWFtolerances");
    }
  }
  // Lagrange interpolation keeps past solutions only; Hermite would also keep f at every step.
  check(ARKStepSetInterpolantType(memory_.get(), ARK_INTERP_LAGRANGE), "ARKStepSetInterpolantType");
}

void Arkode::set_butcher_table() {
  if (method_.trapezoid) {
    double c[2] = {0.0, 1.0}, A[4] = {0.0, 0.0, 0.5, 0.5}, b[2] = {0.5, 0.5};
    ARKodeButcherTable table = ARKodeButcherTable_Create(2, 2, 0, c, A, b, nullptr);
    const int flag = ARKStepSetTables(memory_.get(), 2, 0, table, nullptr);
    ARKodeButcherTable_Free(table);
    check(flag, "ARKStepSetTables");
  } else if (method_.implicit) {
    check(ARKStepSetTableNum(memory_.get(), static_cast<ARKODE_DIRKTableID>(method_.table), ARKODE_ERK_NONE),
          "ARKStepSetTableNum");
  } else {
    check(ARKStepSetTableNum(memory_.get(), ARKODE_DIRK_NONE, static_cast<ARKODE_ERKTableID>(method_.table)),
          "ARKStepSetTableNum");
  }
}

void Arkode::attach_linear_solvers() {
  const model::SecondOrderSystem& system = *system_;
  const Index n = system.size();
  void* memory = memory_.get();
  if (method_.mass_matrix) {
    const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
    mass_matrix_ = assemble_blocks({n, n}, {{0, 0, &I}, {1, 1, &system.M}});
    M_ = sundials::make_sparse(mass_matrix_, context_.get());
    mass_solver_ = std::make_unique<sundials::KluSolver>(y_.get(), M_.get(), context_.get(), method_.klu_ordering);
    check(ARKStepSetMassLinearSolver(memory, mass_solver_->get(), M_.get(), SUNFALSE), "ARKStepSetMassLinearSolver");
    check(ARKStepSetMassFn(memory, mass), "ARKStepSetMassFn");
  }
  jacobian_ = newton_jacobian(system.K);
  if (system.is_nonlinear()) jacobian_pattern_ = jacobian_;
  J_ = sundials::make_sparse(jacobian_, context_.get());
  SUNLinearSolver linear_solver = nullptr;
  if (method_.schur) {
    schur_ = std::make_unique<sundials::SchurSolver>(context_.get(), system, method_.mass_matrix);
    linear_solver = schur_->get();
  } else {
    solver_ = std::make_unique<sundials::KluSolver>(y_.get(), J_.get(), context_.get(), method_.klu_ordering);
    linear_solver = solver_->get();
  }
  check(ARKStepSetLinearSolver(memory, linear_solver, J_.get()), "ARKStepSetLinearSolver");
  check(ARKStepSetJacFn(memory, jacobian), "ARKStepSetJacFn");
  // A nonlinear problem: ARKODE's modified Newton with its own policy for when to rebuild the
  // Jacobian (from the tangent) and refactor; what follows is for the linear problem alone.
  if (system.is_nonlinear()) {
    // At a fixed step a failed Newton solve cannot be retried smaller: give it more iterations
    // than ARKODE's 3, which presume that it can.
    if (!control_.adaptive) check(ARKStepSetMaxNonlinIters(memory, 10), "ARKStepSetMaxNonlinIters");
    check(ARKStepSetPredictorMethod(memory, 1), "ARKStepSetPredictorMethod");
    return;
  }
  check(ARKStepSetLinear(memory, 0), "ARKStepSetLinear");  // linear, constant Jacobian
  // f_i at each stage follows from the stage solution (z - predictor) / (h a_ii): saves one
  // right-hand side (a K product) per implicit stage.
  check(ARKStepSetDeduceImplicitRhs(memory, SUNTRUE), "ARKStepSetDeduceImplicitRhs");
  // The one Newton iteration of a linear problem is exact from any initial guess, so the guess
  // may as well be the trivial predictor z = y_n: its residual needs f(t_stage, y_n), whose K u_n
  // the first-order form's cache already holds from the stage before.
  check(ARKStepSetPredictorMethod(memory, 0), "ARKStepSetPredictorMethod");
  // Refactor only when gamma = h a_ii changes (never at a fixed step of an SDIRK/ESDIRK table).
  check(ARKStepSetLSetupFrequency(memory, INT_MAX / 2), "ARKStepSetLSetupFrequency");
  if (!control_.adaptive) check(ARKStepSetDeltaGammaMax(memory, 1e-8), "ARKStepSetDeltaGammaMax");
}

void Arkode::advance(double t_out, model::State& state) {
  check(ARKStepSetStopTime(memory_.get(), t_out), "ARKStepSetStopTime");
  double t_reached = state.t;
  const int flag = ARKStepEvolve(memory_.get(), t_out, y_.get(), &t_reached, ARK_NORMAL);
  long steps = 0;
  ARKStepGetNumSteps(memory_.get(), &steps);
  if (pending_) {
    try {
      std::rethrow_exception(std::exchange(pending_, nullptr));
    } catch (const ModelError& e) {  // an explicit stage that inverts an element
      throw ModelError(method_.name + ": step " + std::to_string(steps + 1) + ", after t = " + number_text(t_reached) +
                       " s: " + e.what());
    }
  }
  // At a fixed step the error weights are 1 (see reset), so ARKODE's "too much accuracy" test
  // (eps ||y|| > 1) is what a diverging solution trips first: report it as the divergence it is.
  if (flag == ARK_TOO_MUCH_ACC && !control_.adaptive)
    throw SolverError(method_.name + ": the solution diverged (|y| > 1/eps) by t = " + number_text(t_reached) + " s, step " +
                      std::to_string(steps) + "; the step is beyond the method's stability limit");
  if (flag < 0)
    throw SolverError(method_.name + ": failed at t = " + number_text(t_reached) + " s (step " + std::to_string(steps) +
                      "): " + sundials::flag_name(ARKStepGetReturnFlagName(flag)) + last_error_.detail() +
                      (inadmissible_.empty() ? "" : "; the last Newton iterate rejected: " + inadmissible_));
  const Index n = system_->size();
  const auto y = sundials::view(y_.get());
  state.t = t_reached;
  state.u = y.head(n);
  state.v = y.tail(n);
}

Stats Arkode::stats() const {
  Stats s;
  if (!memory_) return s;
  long nfe = 0, nfi = 0, attempts = 0, value = 0;
  ARKStepGetNumSteps(memory_.get(), &s.steps);
  ARKStepGetNumRhsEvals(memory_.get(), &nfe, &nfi);
  s.rhs_evals = nfe + nfi;
  ARKStepGetNumStepAttempts(memory_.get(), &attempts);
  s.failed_steps = attempts - s.steps;
  if (method_.implicit) {
    ARKStepGetNumJacEvals(memory_.get(), &s.jac_evals);
    ARKStepGetNumLinSolvSetups(memory_.get(), &s.lin_setups);
    ARKStepGetNumNonlinSolvIters(memory_.get(), &value);  // one linear solve per Newton iteration
    s.lin_solves = value;
    if (system_ && system_->is_nonlinear()) s.nonlinear_iterations = value;
  }
  if (solver_) s.factorization_s += solver_->setup_seconds();
  if (mass_solver_) s.factorization_s += mass_solver_->setup_seconds();
  if (schur_) s.factorization_s += schur_->factorization_seconds();
  return s;
}

namespace {

ButcherTableau arkode_erk_tableau(ARKODE_ERKTableID id) {
  ARKodeButcherTable table = ARKodeButcherTable_LoadERK(id);
  ButcherTableau t{DenseMatrix(table->stages, table->stages), Vector(table->stages)};
  for (int i = 0; i < table->stages; ++i) {
    t.b[i] = table->b[i];
    for (int j = 0; j < table->stages; ++j) t.A(i, j) = table->A[i][j];
  }
  ARKodeButcherTable_Free(table);
  return t;
}

/// An ARKODE implicit method in its four linear-algebra variants: KLU on J = [[0, I], [-M^-1 K,
/// -M^-1 C]], M as ARKODE's mass matrix (-mass), and the Schur-complement solver (-schur).
void add_implicit(std::vector<IntegratorInfo>& rows, const std::string& name, int order, int table, const std::string& summary) {
  const struct {
    const char* suffix;
    LinearSolver solver;
    const char* how;
  } variants[] = {{"", LinearSolver::klu, "KLU"},
                  {"-mass", LinearSolver::klu_mass, "M as ARKODE's mass matrix, KLU"},
                  {"-schur", LinearSolver::schur, "Schur-complement Cholesky"},
                  {"-mass-schur", LinearSolver::schur_mass, "M as mass matrix, Schur-complement Cholesky"}};
  const bool has_error_estimate = table >= 0;  // the user trapezoid table has no embedding
  for (const auto& v : variants)
    rows.push_back({.name = name + v.suffix,
                    .family = Family::arkode,
                    .order = order,
                    .fixed_step = true,
                    .adaptive = has_error_estimate,
                    .linear_solver = v.solver,
                    .method_id = table,
                    .make = make_arkode,
                    .summary = summary + " (" + v.how + ")",
                    .nonlinear = v.solver == LinearSolver::klu || v.solver == LinearSolver::klu_mass});
}

}  // namespace

std::vector<IntegratorInfo> arkode_rows() {
  std::vector<IntegratorInfo> rows;
  auto erk = [&](const char* name, int order, ARKODE_ERKTableID id, ButcherTableau (*tableau)(), const char* summary) {
    rows.push_back({.name = name,
                    .family = Family::arkode,
                    .order = order,
                    .is_explicit = true,
                    .fixed_step = true,
                    .adaptive = true,
                    .method_id = id,
                    .tableau = tableau,
                    .make = make_arkode,
                    .summary = summary,
                    .nonlinear = true});
  };
  erk(
      "arkode-erk2", 2, ARKODE_HEUN_EULER_2_1_2, [] { return arkode_erk_tableau(ARKODE_HEUN_EULER_2_1_2); },
      "ARKODE explicit Heun-Euler 2(1)");
  erk(
      "arkode-erk3", 3, ARKODE_BOGACKI_SHAMPINE_4_2_3, [] { return arkode_erk_tableau(ARKODE_BOGACKI_SHAMPINE_4_2_3); },
      "ARKODE explicit Bogacki-Shampine 3(2)");
  erk(
      "arkode-erk4", 4, ARKODE_ZONNEVELD_5_3_4, [] { return arkode_erk_tableau(ARKODE_ZONNEVELD_5_3_4); },
      "ARKODE explicit Zonneveld 4(3)");
  erk(
      "arkode-erk5", 5, ARKODE_DORMAND_PRINCE_7_4_5, [] { return arkode_erk_tableau(ARKODE_DORMAND_PRINCE_7_4_5); },
      "ARKODE explicit Dormand-Prince 5(4)");
  add_implicit(rows, "arkode-sdirk2", 2, ARKODE_SDIRK_2_1_2, "ARKODE implicit SDIRK-2-1-2");
  add_implicit(rows, "arkode-ark3", 3, ARKODE_ARK324L2SA_DIRK_4_2_3, "ARKODE implicit ARK324 (its DIRK table)");
  add_implicit(rows, "arkode-esdirk4", 4, ARKODE_ESDIRK436L2SA_6_3_4, "ARKODE implicit ESDIRK436L2SA");
  add_implicit(rows, "arkode-esdirk5", 5, ARKODE_ESDIRK547L2SA_7_4_5, "ARKODE implicit ESDIRK547L2SA");
  add_implicit(rows, "arkode-trapezoid", 2, -1, "ARKODE with the trapezoidal rule as a user Butcher table, fixed step");
  return rows;
}

}  // namespace roifem::integrators
