// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/trapezoid_newton.hpp"

#include <algorithm>

#include "model/internal_force.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::integrators {

TrapezoidNewton::TrapezoidNewton(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
                                 solvers::NewtonOptions options)
    : system_(system),
      inertia_(rule.c_u() * system.M + (2.0 / rule.dt()) * system.C),
      K_t_(system.K),
      J_(system.K + inertia_),  // the union of the two patterns
      K_in_J_(solvers::positions_in(K_t_, J_)),
      inertia_in_J_(solvers::positions_in(inertia_, J_)),
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
                                                double* values = J_.valuePtr();
                                                std::fill(values, values + J_.nonZeros(), 0.0);
                                                const double* k_t = K_t_.valuePtr();
                                                for (std::size_t i = 0; i < K_in_J_.size(); ++i) values[K_in_J_[i]] += k_t[i];
                                                const double* m = inertia_.valuePtr();
                                                for (std::size_t i = 0; i < inertia_in_J_.size(); ++i)
                                                  values[inertia_in_J_[i]] += m[i];
                                                if (J.nonZeros() != J_.nonZeros())
                                                  J = J_;  // the first call: the pattern; later ones copy values only
                                                else
                                                  std::copy(values, values + J_.nonZeros(), J.valuePtr());
                                              }};
  return solvers::newton_solve(equation, u, force_scale, jacobian_, options_);
}

}  // namespace roifem::integrators
