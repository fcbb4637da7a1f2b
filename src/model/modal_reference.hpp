// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The exact solution of M u'' + C u' + K u = sum_k r_k(t) p_k with C = alpha M, by modal
/// superposition: K phi = w^2 M phi (dense, for systems up to a few thousand dofs), and every mode
///   q'' + alpha q' + w^2 q = (phi^T p_k) r_k(t)
/// solved in closed form for the ramp r(t) = min(t / T, 1) (a step when T = 0) from the initial
/// state. With the roots l = -alpha/2 +- sqrt(alpha^2/4 - w^2) (complex), the unit-step response is
///   S(t) = 1/w^2 + A e^{l1 t} + B e^{l2 t},   S(0) = S'(0) = 0,
/// the unit-slope response R(t) = int_0^t S, and a ramp of duration T gives (R(t) - R(t - T)) / T.
/// Errors against it are true errors, not distances to another integrator.
#include "model/second_order_system.hpp"

namespace roifem::model {

class ModalReference {
 public:
  /// Throws InputError unless C = alpha M and every ramp is linear; ModelError above `max_dofs`.
  ModalReference(const SecondOrderSystem& system, const State& initial, Index max_dofs = 6000);
  /// The same system under every load term ramped over `duration` (LoadHistory::with_ramp), its
  /// modes reused: a study of several ramps pays for one eigensolution.
  ModalReference with_ramp(double duration) const;
  Vector displacement(double t) const;
  Vector velocity(double t) const;
  /// The angular eigenfrequencies w_i (rad/s), ascending.
  const Vector& frequencies() const { return omega_; }
  double alpha() const { return alpha_; }

 private:
  double t0_ = 0, alpha_ = 0;
  Vector omega_;
  DenseMatrix modes_;  ///< phi (M-orthonormal), n x n
  Vector q0_, v0_;     ///< modal initial state
  DenseMatrix load_;   ///< phi^T p_k, n x terms
  std::vector<double> ramp_duration_;
  Vector modal(double t, bool derivative) const;
};

}  // namespace roifem::model
