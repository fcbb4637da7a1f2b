// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What the exact solution of M u'' + C u' + K u = f(t) can reach, known before it is computed.
/// With M symmetric positive definite and C, K symmetric positive semi-definite, the energy
/// E = v^T M v / 2 + u^T K u / 2 obeys dE/dt = v^T f - v^T C v <= ||v||_M ||f||_{M^-1}
/// <= sqrt(2 E) ||f||_{M^-1}, so d sqrt(2 E) / dt <= ||f||_{M^-1} and
///   ||v(t)||_M <= sqrt(2 E(t)) <= sqrt(2 E(t_0)) + \int_{t_0}^t ||f(s)||_{M^-1} ds
///              <= sqrt(2 E(t_0)) + (t - t_0) sum_k ||p_k||_{M^-1} max_s |r_k(s)|
/// for the loads f(t) = sum_k r_k(t) p_k (load_history.hpp). The trapezoidal rule keeps the same
/// bound exactly (its discrete energy balance, energy.hpp); a stable method stays near it; a method
/// past its stability limit leaves it by orders of magnitude long before its numbers overflow.
/// Every integrator is held to it (integrator.hpp), whatever its family.
#include "model/second_order_system.hpp"

namespace roifem::model {

class EnergyBound {
 public:
  /// Reads M, K and the load patterns of `system` (kept by pointer: it must outlive the bound).
  EnergyBound(const SecondOrderSystem& system, const State& initial);
  /// The bound on ||v(t)||_M = sqrt(2 x kinetic energy) (sqrt(J)).
  double velocity_norm_bound(double t) const { return initial_ + std::max(0.0, t - t0_) * rate_; }
  /// ||v||_M of a state (sqrt(J)); NaN or inf when v is not finite.
  double velocity_norm(const State& state);

 private:
  const SecondOrderSystem* system_;
  double t0_ = 0;
  double initial_ = 0;    ///< sqrt(2 E(t_0))
  double rate_ = 0;       ///< sum_k ||p_k||_{M^-1} max |r_k|
  Vector mass_diagonal_;  ///< M's diagonal where M is diagonal (else empty: products with M)
  Vector work_;
};

}  // namespace roifem::model
