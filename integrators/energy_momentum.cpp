// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/energy_momentum.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "integrators/callback_guard.hpp"
#include "model/internal_force.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::integrators {

namespace {

std::unique_ptr<Integrator> make_energy_momentum(const IntegratorInfo&, const StepControl& control) {
  return std::make_unique<EnergyMomentum>(control.dt);
}

}  // namespace

EnergyMomentum::EnergyMomentum(double dt, solvers::NewtonOptions options) : dt_(dt), options_(options) {
  options_.line_search = true;
  if (!(dt > 0) || !std::isfinite(dt))
    throw InputError("energy-momentum: dt must be positive and finite, not " + number_text(dt));
}

void EnergyMomentum::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  const Index n = system.size();
  if (initial.u.size() != n || initial.v.size() != n) throw Error("internal: energy-momentum: state size mismatch");
  if (system.internal_force && system.internal_force->has_motion())
    throw InputError(std::string(name()) +
                     " does not take tools on a nonlinear model: their work would need a discrete gradient of its own; "
                     "run trapezoid, or drive the model by [[load]]s");
  if (system.internal_force && !system.internal_force->has_discrete_gradient())
    throw InputError(std::string(name()) + " needs the law's discrete gradient, which " + system.internal_force->describe() +
                     " does not form (the nodal-pressure element at finite strain): run trapezoid, or give element = "
                     "\"tet4\" or \"tet10\"");
  system_ = &system;
  const Stopwatch clock;
  inertia_ = (4.0 / (dt_ * dt_)) * system.M + (2.0 / dt_) * system.C;
  inertia_.makeCompressed();
  K_alg_ = 0.5 * system.K;
  K_alg_.makeCompressed();
  jacobian_pattern_ = solvers::PatternSum(K_alg_, inertia_);
  jacobian_ = solvers::SparseLu();
  grid_ = model::TimeGrid(initial.t, dt_, name());
  k_ = 0;
  f_now_ = system.load.at(initial.t);
  for (Vector* v : {&f_next_, &b_, &u_next_, &work_, &inertia_u_}) v->resize(n);
  stats_ = {};
  stats_.factorization_s = clock.seconds();
}

void EnergyMomentum::algorithmic_force(const Vector& u_a, const Vector& u_b, Vector& f) {
  if (system_->internal_force) {
    system_->internal_force->discrete_gradient(u_a, u_b, f);
    return;
  }
  work_ = 0.5 * (u_a + u_b);
  system_->apply_stiffness(work_, f);
}

void EnergyMomentum::residual(const Vector& u_n, const Vector& u, Vector& r) {
  algorithmic_force(u_n, u, r);
  residual_of_force(u, r);
}

void EnergyMomentum::residual_of_force(const Vector& u, Vector& r) const {
  r *= 2;
  r.noalias() += inertia_ * u;
  r -= b_;
}

void EnergyMomentum::residual_and_jacobian(const Vector& u_n, const Vector& u, Vector& r, SparseMatrix& J) {
  if (system_->internal_force) {
    system_->internal_force->discrete_gradient_and_tangent(u_n, u, r, K_alg_);
  } else {
    algorithmic_force(u_n, u, r);  // K_alg_ is K / 2 throughout
  }
  residual_of_force(u, r);
  jacobian_pattern_.assign(2.0, K_alg_, inertia_, J);  // J = 2 K_alg + inertia
}

void EnergyMomentum::step(model::State& s) {
  ++k_;
  const double t_next = grid_.at(k_);
  system_->load.evaluate(t_next, f_next_);
  // b = f_n + f_{n+1} + 4/dt M v_n + inertia u_n: R(u) = inertia u + 2 f_alg(u_n, u) - b.
  system_->apply_mass(s.v, work_);
  b_ = f_now_ + f_next_ + (4.0 / dt_) * work_;
  inertia_u_.noalias() = inertia_ * s.u;
  b_ += inertia_u_;
  const double scale = std::max(b_.lpNorm<Eigen::Infinity>(), inertia_u_.lpNorm<Eigen::Infinity>());
  const Vector& u_n = s.u;
  const solvers::NonlinearSystem equation{
      .residual = [&](const Vector& u, Vector& r) { residual(u_n, u, r); },
      .residual_and_jacobian = [&](const Vector& u, Vector& r, SparseMatrix& J) { residual_and_jacobian(u_n, u, r, J); }};
  u_next_ = s.u + dt_ * s.v;  // the predictor: constant velocity
  const auto at_step = [&] {
    return std::string(name()) + ": step " + std::to_string(k_) + ", t = " + number_text(t_next) + " s: ";
  };
  const Stopwatch clock;
  solvers::NewtonReport report;
  try {
    try {
      report = solvers::newton_solve(equation, u_next_, scale, jacobian_, options_);
    } catch (const Error&) {
      // From the predictor an iterate can invert an element (a fast step of a soft material) or
      // Newton stall: start once more from u_n, where the last step converged (as the trapezoid).
      ++stats_.failed_steps;
      u_next_ = s.u;
      report = solvers::newton_solve(equation, u_next_, scale, jacobian_, options_);
    }
  } catch (const SolverError& e) {
    throw SolverError(at_step() + e.what());
  } catch (const ModelError& e) {  // an inverted element
    throw ModelError(at_step() + e.what());
  }
  stats_.factorization_s += clock.seconds();
  stats_.nonlinear_iterations += report.iterations();
  stats_.jac_evals += static_cast<long>(report.history.size());
  stats_.lin_setups += report.iterations();
  stats_.lin_solves += report.iterations();
  stats_.rhs_evals += static_cast<long>(report.history.size());
  // v_{n+1} = 2/dt (u_{n+1} - u_n) - v_n.
  s.v = (2.0 / dt_) * (u_next_ - s.u) - s.v;
  s.u = u_next_;
  s.t = t_next;
  std::swap(f_now_, f_next_);
  ++stats_.steps;
}

void EnergyMomentum::advance(double t_out, model::State& state) {
  const long target = grid_.index_of(t_out, k_);
  while (k_ < target) {
    stop_if_asked(state.t);
    step(state);
  }
}

std::optional<IntegratorCheckpoint> EnergyMomentum::checkpoint() const {
  return IntegratorCheckpoint::on_grid(f_now_, grid_.t0(), k_, stats_);
}

void EnergyMomentum::restore(const model::State& state, const IntegratorCheckpoint& saved) {
  IntegratorCheckpoint::OnGrid point = saved.read_on_grid(name(), state.u.size());
  f_now_ = std::move(point.vector);
  grid_ = model::TimeGrid(point.t0, dt_, name());
  k_ = point.k;
  point.stats.factorization_s = stats_.factorization_s;  // this run's own factorization
  stats_ = point.stats;
}

std::vector<IntegratorInfo> energy_momentum_rows() {
  return {{.name = "energy-momentum",
           .order = 2,
           .fixed_step = true,
           .linear_solver = LinearSolver::klu,
           .make = make_energy_momentum,
           .summary = "Gonzalez's energy-momentum method: the midpoint rule with the discrete gradient of the strain "
                      "energy, which an undamped nonlinear run conserves; on a linear model the trapezoidal rule",
           .nonlinear = true,
           .needs_nonlinear = true,
           .needs_discrete_gradient = true}};
}

}  // namespace roifem::integrators
