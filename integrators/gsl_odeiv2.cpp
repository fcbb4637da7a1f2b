// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/gsl_odeiv2.hpp"

#include <gsl/gsl_errno.h>

#include <cmath>
#include <cstring>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/integrator_info.hpp"
#include "model/time_grid.hpp"

namespace roifem::integrators {

GslOdeiv2::GslOdeiv2(std::string name, const gsl_odeiv2_step_type* stepper, StepControl control)
    : name_(std::move(name)), stepper_(stepper), control_(control) {
  gsl_set_error_handler_off();  // GSL's default handler aborts the process; roifem reports errors itself
  model::check_time_step(control_.dt, name_);
}

std::unique_ptr<Integrator> make_gsl(const IntegratorInfo& info, const gsl_odeiv2_step_type* stepper,
                                     const StepControl& control) {
  return std::make_unique<GslOdeiv2>(info.name, stepper, control);
}

bool GslOdeiv2::takes_nonlinear() const { return true; }

int GslOdeiv2::rhs(double t, const double y[], double dydt[], void* self) {
  auto* me = static_cast<GslOdeiv2*>(self);
  // A state the model refuses (an element inverted by a trial step) is GSL_FAILURE, which GSL's
  // adaptive driver retries at half the step; any other error stops it. A solution that presses
  // on an inversion would be retried without end: the max_refused_per_output-th refusal in one
  // output interval stops it, naming the element, the step and the time.
  const int status = guarded_recoverable_callback(
      me->pending_, me->inadmissible_, GSL_EBADFUNC, [&] { me->form_->evaluate(t, y, dydt); }, t);
  if (status == GSL_SUCCESS) ++me->stats_.rhs_evals;
  if (status != 1) return status;
  if (++me->refused_ < max_refused_per_output) return GSL_FAILURE;
  me->pending_ = std::make_exception_ptr(SolverError(
      me->name_ + ": step " + std::to_string(static_cast<long>(me->driver_->e->count) + 1) + ", t = " + number_text(t) +
      " s: " + std::to_string(max_refused_per_output) +
      " states in this output interval inverted an element, each retried at a smaller step (the solution presses on an "
      "inversion; a smaller load or motion, or a finer mesh there); the last: " +
      me->inadmissible_));
  return GSL_EBADFUNC;
}

int GslOdeiv2::jacobian(double t, const double* y, double* dfdy, double dfdt[], void* self) {
  auto* me = static_cast<GslOdeiv2*>(self);
  const int status = guarded_callback(
      me->pending_, GSL_EBADFUNC,
      [&] {
        // A nonlinear system's Jacobian moves with u: -M^-1 K_t(t, u) in its lower left block, at
        // the state the stepper asks for (its implicit steppers' Newton iterations: modified Newton
        // on this matrix until they ask again).
        if (me->system_->is_nonlinear()) {
          const Index n = me->system_->size();
          me->jacobian_.bottomLeftCorner(n, n) = DenseMatrix(me->form_->lower_left(me->form_->stiffness(t, y)));
        }
        const Index m = me->jacobian_.rows();
        std::memcpy(dfdy, me->jacobian_.data(), sizeof(double) * static_cast<std::size_t>(m * m));
        std::fill(dfdt, dfdt + m, 0.0);  // the load's time derivative: ignored by the Newton matrix it feeds
      },
      t);
  if (status == GSL_SUCCESS) ++me->stats_.jac_evals;
  return status;
}

void GslOdeiv2::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  const Index n = system.size();
  if (n > max_gsl_dofs)
    throw InputError(name_ + ": GSL's dense Jacobian is limited to " + std::to_string(max_gsl_dofs) + " dofs; this system has " +
                     std::to_string(n) + " (use an ARKODE or IDA method)");
  system_ = &system;
  form_ = std::make_unique<FirstOrderForm>(system, FirstOrderForm::Mass::inverted);
  jacobian_ = form_->dense_jacobian();
  y_.resize(2 * n);
  y_.head(n) = initial.u;
  y_.tail(n) = initial.v;
  t_ = initial.t;
  stats_ = {};
  pending_ = nullptr;
  inadmissible_.clear();
  system_gsl_ = {rhs, jacobian, static_cast<std::size_t>(2 * n), this};
  // At a fixed step GSL still consults its error control and returns GSL_FAILURE when the estimate
  // would shrink the step: give the control tolerances it can never exceed.
  driver_.reset(control_.adaptive
                    ? gsl_odeiv2_driver_alloc_y_new(&system_gsl_, stepper_, control_.dt, control_.atol, control_.rtol)
                    : gsl_odeiv2_driver_alloc_y_new(&system_gsl_, stepper_, control_.dt, 1e300, 1e300));
  if (!driver_) throw SolverError(name_ + ": cannot allocate the GSL driver");
  gsl_odeiv2_driver_set_nmax(driver_.get(), 10000000);
}

void GslOdeiv2::advance(double t_out, model::State& state) {
  int status = GSL_SUCCESS;
  refused_ = 0;
  if (control_.adaptive) {
    status = gsl_odeiv2_driver_apply(driver_.get(), &t_, t_out, y_.data());
  } else {
    const double steps = (t_out - t_) / control_.dt;
    const auto n = static_cast<unsigned long>(std::lround(steps));
    if (std::abs(steps - static_cast<double>(n)) > 1e-9 * std::max(1.0, steps))
      throw InputError(name_ + ": t_out = " + number_text(t_out) + " s is not on the grid of dt");
    if (n > 0) status = gsl_odeiv2_driver_apply_fixed_step(driver_.get(), &t_, control_.dt, n, y_.data());
  }
  const long step = static_cast<long>(driver_->e->count) + 1;
  if (pending_) {
    try {
      std::rethrow_exception(std::exchange(pending_, nullptr));
    } catch (const ModelError& e) {  // a stage or Newton iterate that inverts an element: GSL cannot retry it smaller
      throw ModelError(name_ + ": step " + std::to_string(step) + ", after t = " + number_text(t_) + " s: " + e.what());
    }
  }
  if (status != GSL_SUCCESS)
    throw SolverError(name_ + ": failed at step " + std::to_string(step) + ", t = " + number_text(t_) + " s: " +
                      gsl_strerror(status) + (inadmissible_.empty() ? "" : "; the last state refused: " + inadmissible_));
  stats_.steps = static_cast<long>(driver_->e->count);  // cumulative; the driver's n is per call
  stats_.failed_steps = static_cast<long>(driver_->e->failed_steps);
  const Index n = system_->size();
  state.t = t_;
  state.u = y_.head(n);
  state.v = y_.tail(n);
}

namespace {

/// GSL's rk4 estimates its error by step doubling and returns the two half steps (ode-initval2's
/// rk4.c: one step of h for the estimate, then two of h/2 as the answer), so what a step of h does
/// is classical RK4 twice at h/2: stability function R(z/2)^2, a limit twice classical RK4's
/// (measured: compare found it stable to the search's upper bracket at 2x before).
ButcherTableau gsl_rk4_step() {
  DenseMatrix A = DenseMatrix::Zero(4, 4);
  A(1, 0) = 0.5;
  A(2, 1) = 0.5;
  A(3, 2) = 1.0;
  Vector b(4);
  b << 1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6;
  ButcherTableau t{DenseMatrix::Zero(8, 8), Vector(8)};
  t.A.topLeftCorner<4, 4>() = A / 2;
  t.A.bottomRightCorner<4, 4>() = A / 2;
  for (int i = 4; i < 8; ++i) t.A.block<1, 4>(i, 0) = b.transpose() / 2;
  t.b.head<4>() = b / 2;  // (a comma initializer here draws a false maybe-uninitialized warning from g++ 12)
  t.b.tail<4>() = b / 2;
  return t;
}

}  // namespace

std::vector<IntegratorInfo> gsl_rows() {
  std::vector<IntegratorInfo> rows;
  auto gsl = [&](const char* name, int order, bool is_explicit, bool fixed, LinearSolver solver, ButcherTableau (*tableau)(),
                 IntegratorMaker make, const char* summary) {
    rows.push_back({.name = name,
                    .family = Family::gsl,
                    .order = order,
                    .is_explicit = is_explicit,
                    .fixed_step = fixed,
                    .adaptive = true,
                    .linear_solver = solver,
                    .tableau = tableau,
                    .make = make,
                    .summary = summary,
                    .nonlinear = true});
  };
  gsl(
      "gsl-bsimp", 6, false, false, LinearSolver::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_bsimp, c); },
      "GSL implicit Bulirsch-Stoer (Bader-Deuflhard), dense Jacobian");
  gsl(
      "gsl-msadams", 12, true, false, LinearSolver::none, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_msadams, c); },
      "GSL variable-order Adams (orders 1-12, explicit)");
  gsl(
      "gsl-msbdf", 5, false, false, LinearSolver::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_msbdf, c); },
      "GSL variable-order BDF (orders 1-5), dense Jacobian");
  gsl(
      "gsl-rk4", 4, true, true, LinearSolver::none, gsl_rk4_step,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk4, c); },
      "GSL classical Runge-Kutta 4 (two half steps per step: GSL's step doubling)");
  gsl(
      "gsl-rk4imp", 4, false, true, LinearSolver::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk4imp, c); },
      "GSL implicit Gauss-Legendre 4, dense Jacobian");
  gsl(
      "gsl-rk8pd", 8, true, false, LinearSolver::none, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk8pd, c); },
      "GSL explicit Prince-Dormand 8(9)");
  return rows;
}

}  // namespace roifem::integrators
