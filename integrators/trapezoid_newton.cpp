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

solvers::NewtonReport TrapezoidNewton::solve(const Vector& b, Vector& u, double force_scale) {
  const model::InternalForce& f_int = *system_.internal_force;
  const solvers::NonlinearSystem equation{.residual =
                                              [&](const Vector& x, Vector& r) {
                                                f_int.force(x, r);
                                                inertia_u_.noalias() = inertia_ * x;
                                                r += inertia_u_ - b;
                                              },
                                          .residual_and_jacobian =
                                              [&](const Vector& x, Vector& r, SparseMatrix& J) {
                                                f_int.force_and_tangent(x, r, K_t_);
                                                inertia_u_.noalias() = inertia_ * x;
                                                r += inertia_u_ - b;
                                                jacobian_pattern_.assign(1.0, K_t_, inertia_, J);
                                              }};
  return solvers::newton_solve(equation, u, force_scale, jacobian_, options_);
}

}  // namespace roifem::integrators
