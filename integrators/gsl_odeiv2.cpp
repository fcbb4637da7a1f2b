#include "integrators/gsl_odeiv2.hpp"

#include <gsl/gsl_errno.h>

#include <cmath>
#include <cstring>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/integrator_table.hpp"

namespace roifem::integrators {

GslOdeiv2::GslOdeiv2(std::string name, const gsl_odeiv2_step_type* stepper, StepControl control)
    : name_(std::move(name)), stepper_(stepper), control_(control) {
  gsl_set_error_handler_off();  // GSL's default handler aborts the process; roifem reports errors itself
  if (!(control_.dt > 0) || !std::isfinite(control_.dt))
    throw InputError(name_ + ": time step dt = " + std::to_string(control_.dt) + " s must be positive");
}

std::unique_ptr<Integrator> make_gsl(const IntegratorInfo& info, const gsl_odeiv2_step_type* stepper,
                                     const StepControl& control) {
  return std::make_unique<GslOdeiv2>(info.name, stepper, control);
}

int GslOdeiv2::rhs(double t, const double y[], double dydt[], void* self) {
  auto* me = static_cast<GslOdeiv2*>(self);
  const int status = guarded_callback(me->pending_, GSL_EBADFUNC, [&] { me->form_->evaluate(t, y, dydt); });
  if (status == GSL_SUCCESS) ++me->stats_.rhs_evals;
  return status;
}

int GslOdeiv2::jacobian(double, const double*, double* dfdy, double dfdt[], void* self) {
  auto* me = static_cast<GslOdeiv2*>(self);
  const Index m = me->jacobian_.rows();
  std::memcpy(dfdy, me->jacobian_.data(), sizeof(double) * static_cast<std::size_t>(m * m));
  std::fill(dfdt, dfdt + m, 0.0);  // the load's time derivative: ignored by the Newton matrix it feeds
  ++me->stats_.jac_evals;
  return GSL_SUCCESS;
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
  if (control_.adaptive) {
    status = gsl_odeiv2_driver_apply(driver_.get(), &t_, t_out, y_.data());
  } else {
    const double steps = (t_out - t_) / control_.dt;
    const auto n = static_cast<unsigned long>(std::lround(steps));
    if (std::abs(steps - static_cast<double>(n)) > 1e-9 * std::max(1.0, steps))
      throw InputError(name_ + ": t_out = " + number_text(t_out) + " s is not on the grid of dt");
    if (n > 0) status = gsl_odeiv2_driver_apply_fixed_step(driver_.get(), &t_, control_.dt, n, y_.data());
  }
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  if (status != GSL_SUCCESS) throw SolverError(name_ + ": failed at t = " + number_text(t_) + " s: " + gsl_strerror(status));
  stats_.steps = static_cast<long>(driver_->e->count);  // cumulative; the driver's n is per call
  stats_.failed_steps = static_cast<long>(driver_->e->failed_steps);
  const Index n = system_->size();
  state.t = t_;
  state.u = y_.head(n);
  state.v = y_.tail(n);
}

}  // namespace roifem::integrators
