// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/trapezoid_newton.hpp"

#include "model/internal_force.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::integrators {

TrapezoidNewton::TrapezoidNewton(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
                                 solvers::NewtonOptions options)
    : system_(system),
      inertia_(rule.c_u() * system.M + (2.0 / rule.dt()) * system.C),
      K_t_(system.K),
      jacobian_pattern_(K_t_, inertia_),
      options_(options) {
  K_t_.makeCompressed();
  inertia_.makeCompressed();
}

solvers::NonlinearSystem TrapezoidNewton::equation(double t, const Vector& b) {
  const model::InternalForce& f_int = *system_.internal_force;
  return {.residual =
              [&f_int, &b, t, this](const Vector& x, Vector& r) {
                f_int.force(t, x, r);
                inertia_u_.noalias() = inertia_ * x;
                r += inertia_u_ - b;
              },
          .residual_and_jacobian =
              [&f_int, &b, t, this](const Vector& x, Vector& r, SparseMatrix& J) {
                f_int.force_and_tangent(t, x, r, K_t_);
                inertia_u_.noalias() = inertia_ * x;
                r += inertia_u_ - b;
                jacobian_pattern_.assign(1.0, K_t_, inertia_, J);
              }};
}

solvers::NewtonReport TrapezoidNewton::solve(double t, const Vector& b, Vector& u, double force_scale) {
  return solvers::newton_solve(equation(t, b), u, force_scale, jacobian_, options_);
}

solvers::NewtonReport TrapezoidNewton::solve_carefully(double t, const Vector& b, Vector& u, double force_scale,
                                                       bool& indefinite) {
  solvers::NewtonOptions careful = options_;
  careful.line_search = true;
  const Vector start = u;
  indefinite = false;
  try {
    return solvers::newton_solve(equation(t, b), u, force_scale, jacobian_, careful);
  } catch (const solvers::IndefiniteJacobian&) {
    indefinite = true;
    u = start;
    return solvers::newton_solve(equation(t, b), u, force_scale, indefinite_jacobian_, careful);
  }
}

}  // namespace roifem::integrators
