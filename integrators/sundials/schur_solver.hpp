// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A custom SUNLinearSolver for ARKODE's Newton matrix on the first-order form of
/// M u'' + C u' + K u = f. ARKODE asks to solve A x = b with
///   A = I - gamma J = [[I, -gamma I], [gamma M^-1 K, I + gamma M^-1 C]]       (lumped M), or
///   A = M_ - gamma J = [[I, -gamma I], [gamma K, M + gamma C]]               (M as mass matrix).
/// Eliminating x_v = (x_u - b_u) / gamma leaves one symmetric positive definite system of size n,
///   S x_u = gamma (M b_v or b_v) + (M + gamma C) b_u,   S = M + gamma C + gamma^2 K,
/// factored by CHOLMOD and refactored only when gamma changes: the same work per stage as the
/// trapezoidal rule's one solve (no product with K: M and C are cheap), instead of a KLU solve of
/// the unsymmetric 2n system. The division by gamma costs no accuracy where it matters: x_u - b_u
/// carries a rounding error of about eps |x_u| ~ eps h |v|, so x_v (the change of v over the stage)
/// is off by about eps |v| / a_ii, a rounding error of v itself.
/// gamma is read from A itself (its top-right block is -gamma I): ARKODE forms A before setup.
#include "integrators/sundials/handles.hpp"
#include "model/second_order_system.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::integrators::sundials {

class SchurSolver {
 public:
  SchurSolver(SUNContext context, const model::SecondOrderSystem& system, bool mass_form);
  SchurSolver(const SchurSolver&) = delete;
  SchurSolver& operator=(const SchurSolver&) = delete;
  ~SchurSolver();
  SUNLinearSolver get() const { return solver_; }
  long factorizations() const { return factorizations_; }
  /// Seconds spent in CHOLMOD's analysis and factorizations.
  double factorization_seconds() const { return factorization_s_; }

 private:
  static int setup(SUNLinearSolver S, SUNMatrix A);
  static int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol);

  SUNLinearSolver solver_ = nullptr;
  const model::SecondOrderSystem& system_;
  bool mass_form_;
  double gamma_ = -1;
  solvers::Cholesky schur_;
  roifem::Vector rhs_, work_;
  double factorization_s_ = 0;
  long factorizations_ = 0;
};

}  // namespace roifem::integrators::sundials
