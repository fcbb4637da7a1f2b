// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/trapezoid.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/modal_elimination.hpp"
#include "solvers/newton.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_trapezoid(const IntegratorInfo& info, const StepControl& control) {
  if (info.linear_solver == LinearSolver::jacobi_cg) return std::make_unique<Trapezoid>(control.dt, solvers::CgSettings{});
  return std::make_unique<Trapezoid>(control.dt);
}

Trapezoid::Trapezoid(double dt) : rule_(dt) {}

Trapezoid::Trapezoid(double dt, solvers::CgSettings cg) : Trapezoid(dt) { cg_ = cg; }

void Trapezoid::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  system_ = &system;
  const Index n = system.size();
  if (initial.u.size() != n || initial.v.size() != n) throw Error("internal: trapezoid: state size mismatch");
  const Stopwatch clock;
  K_eff_.reset();
  newton_.reset();
  eliminates_modal_ = !cg_ && system.modal && system.damping.is_mass_proportional() && !system.is_nonlinear();
  try {
    if (system.is_nonlinear())
      newton_ = std::make_unique<TrapezoidNewton>(system, rule_);
    else if (cg_)
      K_eff_ = std::make_unique<ConjugateGradients>(system, rule_, *cg_);
    else if (eliminates_modal_)
      K_eff_ = std::make_unique<ModalElimination>(system, rule_.dt());
    else
      K_eff_ = std::make_unique<DirectSolve>(system, rule_);
  } catch (const solvers::NotPositiveDefinite& e) {
    throw SolverError(std::string(name()) + ": K + 2/dt C + 4/dt^2 M is not positive definite: " + e.what());
  }
  grid_ = model::TimeGrid(initial.t, rule_.dt(), name());
  k_ = 0;
  iterations_before_ = 0;
  a_ = model::AverageAcceleration::consistent_acceleration(system, initial);
  f_.resize(n);
  u_next_.resize(n);
  work_.resize(n);
  stats_ = {};
  stats_.lin_setups = newton_ ? 0 : 1;
  stats_.factorization_s = clock.seconds();
}

void Trapezoid::solve_nonlinear(const model::State& s) {
  // b = f + M w; the tolerance's scale: the largest of the load, the history's inertia and the
  // internal force it balances.
  system_->apply_mass(work_, u_next_);
  f_ += u_next_;
  const double scale = std::max(f_.lpNorm<Eigen::Infinity>(), (system_->M * a_).lpNorm<Eigen::Infinity>());
  // The predictor: u_n, where the last step converged. The rule's own (u_n + dt v_n + dt^2/2 a_n)
  // carries the acceleration of the modes it leaves undamped, and on the paper brain it landed
  // where the tangent was indefinite in most steps, each then retried from u_n
  // (docs/design-figures.md).
  u_next_ = s.u;
  const Stopwatch clock;
  solvers::NewtonReport report;
  try {
    report = newton_->solve(s.t, f_, u_next_, scale);
  } catch (const Error&) {
    // An iterate can land where the tangent is indefinite (a soft material compressed by the step's
    // inertia) or an element inverts: start once more from u_n, with a line search, and by LU where
    // the Jacobian is indefinite there too.
    ++stats_.failed_steps;
    u_next_ = s.u;
    bool indefinite = false;
    report = newton_->solve_carefully(s.t, f_, u_next_, scale, indefinite);
    stats_.indefinite_steps += indefinite ? 1 : 0;
  }
  stats_.factorization_s += clock.seconds();
  stats_.nonlinear_iterations += report.iterations();
  stats_.jac_evals += static_cast<long>(report.history.size());
  stats_.lin_setups += report.iterations();
  stats_.lin_solves += report.iterations();
  stats_.rhs_evals += static_cast<long>(report.history.size());
}

void Trapezoid::step(model::State& s) {
  const double dt = rule_.dt();
  ++k_;
  s.t = grid_.at(k_);
  system_->load.evaluate(s.t, f_);
  rule_.history(*system_, s, a_, f_, work_);
  const auto at_step = [&] {
    return std::string(name()) + ": step " + std::to_string(k_) + ", t = " + number_text(s.t) + " s: ";
  };
  if (newton_) {
    try {
      solve_nonlinear(s);
    } catch (const SolverError& e) {
      throw SolverError(at_step() + e.what());
    } catch (const ModelError& e) {  // an inverted element
      throw ModelError(at_step() + e.what());
    }
    rule_.advance(s, a_, u_next_, work_);
    ++stats_.steps;
    return;
  }
  if (K_eff_->uses_initial_guess()) u_next_ = s.u + dt * s.v + (0.5 * dt * dt) * a_;  // constant acceleration
  try {
    K_eff_->solve(f_, work_, u_next_);
  } catch (const SolverError& e) {
    throw SolverError(at_step() + e.what());
  }
  stats_.lin_iterations = iterations_before_ + K_eff_->iterations();
  rule_.advance(s, a_, u_next_, work_);
  ++stats_.steps;
  ++stats_.rhs_evals;
  ++stats_.lin_solves;
}

void Trapezoid::advance(double t_out, model::State& state) {
  const long target = grid_.index_of(t_out, k_);
  while (k_ < target) {
    stop_if_asked(state.t);
    step(state);
  }
}

std::optional<IntegratorCheckpoint> Trapezoid::checkpoint() const {
  return IntegratorCheckpoint::on_grid(a_, grid_.t0(), k_, stats_);
}

void Trapezoid::restore(const model::State& state, const IntegratorCheckpoint& saved) {
  IntegratorCheckpoint::OnGrid point = saved.read_on_grid(name(), state.u.size());
  a_ = std::move(point.vector);
  grid_ = model::TimeGrid(point.t0, rule_.dt(), name());
  k_ = point.k;
  point.stats.factorization_s = stats_.factorization_s;  // this run's own factorization
  stats_ = point.stats;
  if (K_eff_) iterations_before_ = stats_.lin_iterations - K_eff_->iterations();  // an iterative solver's count goes on
}

bool Trapezoid::absorb_change(const model::SecondOrderSystem& system, const model::SystemChange& change,
                              const model::State& state) {
  // K_eff = K + c M with C = alpha M (SystemChange::apply keeps it so).
  const Stopwatch clock;
  if (&system != system_ || !K_eff_ || eliminates_modal_ ||
      !K_eff_->update(change.dofs, change.effective(rule_.mass_factor(system.damping)))) {
    const Stats before = stats_;
    prepare(system, state);  // the grid starts afresh at state.t, a level of the old one
    stats_ += before;
    iterations_before_ = stats_.lin_iterations;  // an iterative K_eff's count goes on from the sum
    return false;
  }
  stats_.factorization_s += clock.seconds();
  ++stats_.system_changes;
  // The rule's energy identity needs M a_n = f_n - C v_n - K u_n with the changed operators.
  a_ = model::AverageAcceleration::consistent_acceleration(system, state);
  return false;
}

std::vector<IntegratorInfo> trapezoid_rows() {
  return {
      {.name = "trapezoid",
       .order = 2,
       .fixed_step = true,
       .linear_solver = LinearSolver::cholmod,
       .make = make_trapezoid,
       .summary = "the paper's trapezoidal rule (Newmark average acceleration), K_eff factored once; Newton on a nonlinear model",
       .nonlinear = true},
      {.name = "trapezoid-cg",
       .order = 2,
       .fixed_step = true,
       .linear_solver = LinearSolver::jacobi_cg,
       .make = make_trapezoid,
       .summary = "the same rule with K_eff solved by Jacobi-preconditioned CG (no factor; for the largest brains)"}};
}

}  // namespace roifem::integrators
