#include "integrators/trapezoid.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/modal_elimination.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_trapezoid(const IntegratorInfo& info, const StepControl& control) {
  if (info.linear_solver == LinearSolver::jacobi_cg) return std::make_unique<Trapezoid>(control.dt, solvers::CgSettings{});
  return std::make_unique<Trapezoid>(control.dt);
}

Trapezoid::Trapezoid(double dt) : dt_(dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw InputError("trapezoid: time step dt = " + number_text(dt) + " s must be positive");
}

Trapezoid::Trapezoid(double dt, solvers::CgSettings cg) : Trapezoid(dt) { cg_ = cg; }

void Trapezoid::reset(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  const Index n = system.size();
  if (initial.u.size() != n || initial.v.size() != n) throw Error("internal: trapezoid: state size mismatch");
  const Stopwatch clock;
  K_eff_.reset();
  eliminates_modal_ = !cg_ && system.modal && system.damping.is_mass_proportional();
  try {
    if (cg_)
      K_eff_ = std::make_unique<ConjugateGradients>(system, dt_, *cg_);
    else if (eliminates_modal_)
      K_eff_ = std::make_unique<ModalElimination>(system, dt_);
    else
      K_eff_ = std::make_unique<DirectSolve>(system, dt_);
  } catch (const solvers::NotPositiveDefinite& e) {
    throw SolverError(std::string(name()) + ": K + 2/dt C + 4/dt^2 M is not positive definite: " + e.what());
  }
  t0_ = initial.t;
  k_ = 0;
  // Consistent initial acceleration: M a_0 = f(t_0) - C v_0 - K u_0.
  f_ = system.load.at(initial.t);
  const Vector r = f_ - system.C * initial.v - system.K * initial.u;
  solvers::Cholesky mass;
  mass.compute(system.M);
  a_ = mass.solve(r);
  u_next_.resize(n);
  work_.resize(n);
  stats_ = {};
  stats_.lin_setups = 1;
  stats_.factorization_s = clock.seconds();
}

void Trapezoid::step(model::State& s) {
  const double c_u = 4.0 / (dt_ * dt_), c_v = 4.0 / dt_;
  ++k_;
  s.t = t0_ + static_cast<double>(k_) * dt_;
  system_->load.evaluate(s.t, f_);
  // K_eff u_{n+1} = f + M (c_u u + c_v v + a) + C (2/dt u + v); with C = alpha M one product with M.
  const model::Damping& damping = system_->damping;
  if (damping.is_mass_proportional()) {
    work_ = (c_u + damping.alpha * 2.0 / dt_) * s.u + (c_v + damping.alpha) * s.v + a_;
  } else {
    work_ = (2.0 / dt_) * s.u + s.v;
    f_.noalias() += system_->C * work_;
    work_ = c_u * s.u + c_v * s.v + a_;
  }
  if (K_eff_->uses_initial_guess()) u_next_ = s.u + dt_ * s.v + (0.5 * dt_ * dt_) * a_;  // constant acceleration
  try {
    K_eff_->solve(f_, work_, u_next_);
  } catch (const SolverError& e) {
    throw SolverError(std::string(name()) + ": step " + std::to_string(k_) + ", t = " + number_text(s.t) + " s: " + e.what());
  }
  stats_.lin_iterations = K_eff_->iterations();
  // a_{n+1} = c_u (u_{n+1} - u_n) - c_v v_n - a_n, then v and u.
  work_ = c_u * (u_next_ - s.u) - c_v * s.v - a_;
  s.v += 0.5 * dt_ * (a_ + work_);
  a_.swap(work_);
  s.u.swap(u_next_);
  ++stats_.steps;
  ++stats_.rhs_evals;
  ++stats_.lin_solves;
  if (!s.u.allFinite())
    throw SolverError(std::string(name()) + ": non-finite displacement at step " + std::to_string(k_) + ", t = " + number_text(s.t) + " s");
}

void Trapezoid::advance_to(double t_out, model::State& state) {
  if (!system_) throw Error("internal: trapezoid: advance_to before reset");
  const double steps = (t_out - t0_) / dt_;
  const long target = std::lround(steps);
  if (std::abs(steps - static_cast<double>(target)) > 1e-9 * std::max(1.0, std::abs(steps)) || target < k_)
    throw InputError("trapezoid: t_out = " + number_text(t_out) + " s is not a later point of the grid t0 + k dt");
  while (k_ < target) step(state);
}

}  // namespace roifem::integrators
