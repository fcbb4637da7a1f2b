// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule's implicit equation for a nonlinear system (model/internal_force.hpp).
/// With the history b = f_{n+1} + M w_n (+ C (2/dt u_n + v_n)) of model/average_acceleration.hpp,
/// the linear rule solves K_eff u = b; the nonlinear one solves
///   R(u) = (4/dt^2 M + 2/dt C) u + f_int(u) - b = 0
/// by Newton (solvers/newton.hpp), its Jacobian 4/dt^2 M + 2/dt C + K_t(u) refactorized by CHOLMOD
/// on the symbolic analysis of the first step (the pattern never changes). With f_int = K u it is
/// the linear rule, solved in one iteration. Where the Jacobian is not positive definite (a
/// compressed element of a nearly incompressible law turns its tangent indefinite long before it
/// inverts: mu = 12 Pa against kappa (J - 1) at 0.3% compression on the paper brain), the caller
/// may solve the step again on KLU's LU factorization of the same matrix (solve_carefully, on its
/// own analysis): Newton needs a nonsingular Jacobian, not a definite one. An iteration allocates
/// nothing: the Jacobian's pattern (K's and the inertia's) is built once, and each iteration adds
/// K_t's and the inertia's values into it through index maps.
#include <vector>

#include "model/average_acceleration.hpp"
#include "model/second_order_system.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/newton.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::integrators {

class TrapezoidNewton {
 public:
  /// The system must outlive this.
  TrapezoidNewton(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule,
                  solvers::NewtonOptions options = {});
  /// u: the predictor on entry, u_{n+1} on return, at t = t_{n+1}. `force_scale`: the residual
  /// tolerance's scale (N). Throws SolverError (no convergence) or ModelError (an inverted element)
  /// for the caller to name its step.
  solvers::NewtonReport solve(double t, const Vector& b, Vector& u, double force_scale);
  /// A retry after solve() failed: from u (the last converged state), with a line search, and by
  /// LU where the Jacobian is not positive definite (solvers::IndefiniteJacobian). Sets `indefinite`.
  solvers::NewtonReport solve_carefully(double t, const Vector& b, Vector& u, double force_scale, bool& indefinite);
  const solvers::NewtonOptions& options() const { return options_; }

 private:
  const model::SecondOrderSystem& system_;
  SparseMatrix inertia_;                  ///< 4/dt^2 M + 2/dt C
  SparseMatrix K_t_;                      ///< the tangent, in K's pattern
  solvers::PatternSum jacobian_pattern_;  ///< K_t + inertia, in the union of their patterns
  solvers::NewtonOptions options_;
  /// CHOLMOD's choice (supernodal on the brains): fewer Newton iterations and less time than a
  /// simplicial factor (docs/design-figures.md).
  solvers::Cholesky jacobian_;
  solvers::SparseLu indefinite_jacobian_;
  /// The step's equation: R(u) = inertia u + f_int(t, u) - b, and its Jacobian.
  solvers::NonlinearSystem equation(double t, const Vector& b);
  Vector inertia_u_;
};

}  // namespace roifem::integrators
