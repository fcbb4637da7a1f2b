// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule's linear solve for a reduced system with modal coordinates (Craig-Bampton,
/// POD), with the modal coordinates eliminated in closed form.
///
/// The system's last k dofs q are modal coordinates (SecondOrderSystem::modal, ModalBlock): their
/// mass is the identity, their stiffness the diagonal Lambda, and they couple to the ROI dofs d
/// through the mass alone, by a dense block B on the interface rows (C = alpha M):
///   M = [[M_dd, B], [B^T, I]],   K = [[K_dd, 0], [0, Lambda]].
/// With K_eff = K + c M (c = 4/dt^2 + 2 alpha/dt) and D = Lambda + c I (diagonal), the step's
/// K_eff [x_d; x_q] = [r_d; r_q] is
///   (K_eff,dd - c^2 B D^-1 B^T) x_d = r_d - c B D^-1 r_q,   x_q = D^-1 (r_q - c B^T x_d).
/// The correction c^2 B D^-1 B^T lands on the interface block, which K_eff,dd has dense already:
/// the factor is as large as plain condensation's, where factoring K_eff whole adds a dense modal
/// block (on the paper's setup 1 with 200 modes: 1.5x the solve time). Each step reads B twice
/// and one dense interface block, G - c B D^-1 B^T (G: M_dd's interface block), once.
#include <vector>

#include "integrators/effective_stiffness.hpp"
#include "model/second_order_system.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::integrators {

class ModalElimination final : public EffectiveStiffnessSolver {
 public:
  /// The elimination of `system`'s declared modal coordinates (system.modal; C = alpha M) from
  /// K_eff = K + c M with c = 4/dt^2 + 2 alpha/dt. Throws solvers::NotPositiveDefinite as a
  /// factorization does.
  ModalElimination(const model::SecondOrderSystem& system, double dt);

  /// x = K_eff^-1 (f + M w): the trapezoidal rule's step with w = (4/dt^2 + 2 alpha/dt) u +
  /// (4/dt + alpha) v + a. x must not alias f or w.
  void solve(const Vector& f, const Vector& w, Vector& x) override;

 private:
  Index n_d_ = 0;  // ROI dofs, first
  double c_ = 0;
  SparseMatrix M_dd_;               // the split M's sparse part over d (diagonal for a lumped M)
  std::vector<Index> interface_;    // rows of B and of the interface mass block
  DenseMatrix interface_operator_;  // G - c B D^-1 B^T (G: M_dd's interface block; lower triangle read)
  DenseMatrix B_;                   // #interface x k
  Vector D_inverse_;                // (Lambda + c I)^-1
  solvers::Cholesky factor_;        // K_eff,dd - c^2 B D^-1 B^T, interface last
  Vector r_d_, w_i_, x_i_, product_i_, r_q_, y_q_;
};

}  // namespace roifem::integrators
