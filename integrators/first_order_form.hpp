// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The first-order form y = [u; v] of M u'' + C u' + K u = f(t) that ARKODE and GSL integrate:
///   u' = v,   v' = M^-1 (f(t) - C v - K u)          (or, with M kept as a mass matrix,
///   u' = v,   M v' = f(t) - C v - K u),
/// with its Jacobian J = [[0, I], [-M^-1 K, -M^-1 C]]. A nonlinear system's f_int(u) takes K u's
/// place in evaluate() (model/internal_force.hpp), and its tangent K_t(u) K's place in the
/// Jacobian, which then moves with u (stiffness()). M^-1 is a product for a lumped M and a Cholesky
/// solve for the full M of a Guyan, Craig-Bampton or POD model (MassInverse).
#include <memory>

#include "model/mass_inverse.hpp"
#include "model/second_order_system.hpp"

namespace roifem::integrators {

class FirstOrderForm {
 public:
  enum class Mass { inverted, kept };  ///< v' = M^-1 (...), or M v' = (...) for a mass-matrix solver
  /// The system must outlive the form.
  FirstOrderForm(const model::SecondOrderSystem& system, Mass mass);
  Index size() const { return 2 * system_.size(); }
  /// ydot = y'(t, y). K u, the costly part, is kept keyed by u's exact values (and t's, where
  /// tools move a nonlinear law's nodes): a stage often evaluates at the u of the evaluation before.
  void evaluate(double t, const double* y, double* ydot);
  /// The stiffness at (t, y's u): the system's K, or a nonlinear system's tangent K_t(t, u) (in
  /// K's pattern; valid until the next call).
  const SparseMatrix& stiffness(double t, const double* y);
  /// -M^-1 K (of the system's K, or of a tangent) and -M^-1 C, the Jacobian's lower blocks
  /// (sparse: see MassInverse::apply).
  SparseMatrix lower_left(const SparseMatrix& K) const;
  SparseMatrix lower_left() const { return lower_left(system_.K); }
  SparseMatrix lower_right() const;
  /// The whole Jacobian, dense (row-major), for GSL.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dense_jacobian() const;

 private:
  const model::SecondOrderSystem& system_;
  Mass mass_;
  std::unique_ptr<model::MassInverse> mass_inverse_;  // with Mass::inverted
  Vector force_, work_, cached_u_, cached_Ku_;
  double cached_t_ = 0;
  Vector tangent_u_, tangent_force_;  // stiffness()'s
  SparseMatrix tangent_;
};

}  // namespace roifem::integrators
