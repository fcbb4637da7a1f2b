// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/newton.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::solvers {

namespace {

template <class LinearSolver>
NewtonReport newton(const NonlinearSystem& system, Vector& x, double force_scale, LinearSolver& solver, const NewtonOptions& o) {
  NewtonReport report;
  Vector r(x.size()), dx(x.size()), trial;
  SparseMatrix J;
  const double residual_target = o.residual_tolerance * force_scale;
  for (int k = 0;; ++k) {
    system.residual_and_jacobian(x, r, J);
    const double residual = r.lpNorm<Eigen::Infinity>();
    report.history.push_back({k, residual, 0.0});
    if (!std::isfinite(residual)) throw SolverError(format("Newton: the residual is not finite at iteration %d", k));
    const double last_increment = k > 0 ? report.history[static_cast<std::size_t>(k - 1)].increment : INFINITY;
    const double increment_target = o.increment_tolerance * std::max(x.lpNorm<Eigen::Infinity>(), o.increment_floor);
    // Converged: the residual within its tolerance and the last correction negligible. A zero
    // residual at the start (nothing loaded) needs no correction at all. At small strain the
    // residual has a rounding floor above the tolerance (the stress is a difference of O(mu)
    // terms): a negligible correction that left the residual no lower than half is that floor.
    const bool at_floor = k >= 2 && residual > 0.5 * report.history[static_cast<std::size_t>(k - 1)].residual;
    if ((residual <= residual_target || at_floor) && (last_increment <= increment_target || residual == 0)) return report;
    if (k == o.max_iterations)
      throw SolverError(
          format("Newton did not converge in %d iterations: residual %.3e N (tolerance %.3e), last "
                 "correction %.3e m (tolerance %.3e)",
                 o.max_iterations, residual, residual_target, last_increment, increment_target));
    try {
      if (k == 0 && solver.size() != J.rows()) solver.analyze(J);
      solver.factorize(J);
    } catch (const NotPositiveDefinite& e) {
      throw IndefiniteJacobian(
          format("Newton: the tangent is singular or not positive definite at iteration %d%s: the "
                 "structure is unstable at this load, or the iterate far from the solution",
                 k, e.column >= 0 ? format(" (column %lld)", static_cast<long long>(e.column)).c_str() : ""));
    } catch (const SolverError& e) {  // SparseLu: singular
      throw SolverError(format("Newton: the Jacobian at iteration %d: %s", k, e.what()));
    }
    solver.solve(-r, dx);
    if (o.line_search) {
      // ||r(x + s dx)||_2 <= (1 - 1e-4 s) ||r(x)||_2, s = 1, 1/2, ... 1/256; the last tried is taken.
      const double r0 = r.norm();
      double step = 1;
      for (int halving = 0; halving < 8; ++halving, step *= 0.5) {
        trial = x + step * dx;
        try {
          system.residual(trial, r);
        } catch (const ModelError&) {  // an element inverted at the trial point: shorter
          continue;
        }
        if (std::isfinite(r.norm()) && r.norm() <= (1 - 1e-4 * step) * r0) break;
      }
      dx *= step;
    }
    x += dx;
    report.history.back().increment = dx.lpNorm<Eigen::Infinity>();
  }
}

}  // namespace

NewtonReport newton_solve(const NonlinearSystem& system, Vector& x, double force_scale, Cholesky& solver,
                          const NewtonOptions& options) {
  return newton(system, x, force_scale, solver, options);
}

NewtonReport newton_solve(const NonlinearSystem& system, Vector& x, double force_scale, SparseLu& solver,
                          const NewtonOptions& options) {
  return newton(system, x, force_scale, solver, options);
}

}  // namespace roifem::solvers
