// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Newton's method for a nonlinear system r(x) = 0 with a symmetric positive definite Jacobian,
/// by a sparse Cholesky factor (CHOLMOD) analysed once and refactorized on every iteration:
///   J(x_k) dx = -r(x_k),  x_{k+1} = x_k + dx.
/// The convergence test, stated once for every user (static solves, the trapezoidal rule):
///   ||r(x_k)||_inf <= residual_tolerance * scale   and   ||dx||_inf <= increment_tolerance * max(||x||_inf, increment_floor)
/// where `scale` is the caller's force scale (the load, or the first residual); or, where the
/// residual has reached its rounding floor (a negligible correction left it no lower than half),
/// the increment test alone. An iteration that
/// does not meet both within max_iterations, or whose residual turns non-finite, is a SolverError
/// that the caller prefixes with its step and time; nothing is extrapolated.
#include <functional>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/types.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/sparse_lu.hpp"

namespace roifem::solvers {

struct NewtonOptions {
  double residual_tolerance = 1e-10;  ///< relative to the force scale
  /// relative to ||x||_inf: in the quadratic regime a correction d leaves an error of order d^2, so
  /// 1e-8 leaves ~1e-16 once the residual test holds (1e-10 cost one more iteration per step)
  double increment_tolerance = 1e-8;
  double increment_floor = 1e-12;  ///< m: below this ||x|| the increment test is absolute
  int max_iterations = 25;
  /// Backtracking (Armijo on ||r||_2, halving up to 8 times): a correction that does not lower the
  /// residual is shortened. Off by default: it costs a residual per iteration.
  bool line_search = false;
};

/// One iteration's figures (iteration 0: the residual before the first solve).
struct NewtonIterate {
  int iteration = 0;
  double residual = 0;   ///< ||r||_inf
  double increment = 0;  ///< ||dx||_inf of the solve that followed (0 at the last)
};

struct NewtonReport {
  std::vector<NewtonIterate> history;
  int iterations() const { return history.empty() ? 0 : static_cast<int>(history.size()) - 1; }
};

/// The Cholesky form's failure when a Jacobian is not positive definite: a symmetric indefinite
/// Jacobian, which an LU factorization still solves (newton_solve with SparseLu).
class IndefiniteJacobian : public SolverError {
 public:
  explicit IndefiniteJacobian(const std::string& what) : SolverError(what) {}
};

/// What Newton solves: the residual, and the residual with its Jacobian (pattern fixed).
struct NonlinearSystem {
  std::function<void(const Vector& x, Vector& r)> residual;
  std::function<void(const Vector& x, Vector& r, SparseMatrix& J)> residual_and_jacobian;
};

/// Solves r(x) = 0 from the initial x (overwritten with the solution). `solver` keeps its
/// analysis between calls (the pattern does not change). Throws SolverError with the history's
/// last figures when it does not converge.
NewtonReport newton_solve(const NonlinearSystem& system, Vector& x, double force_scale, Cholesky& solver,
                          const NewtonOptions& options = {});
/// The same with an unsymmetric Jacobian, by LU.
NewtonReport newton_solve(const NonlinearSystem& system, Vector& x, double force_scale, SparseLu& solver,
                          const NewtonOptions& options = {});

}  // namespace roifem::solvers
