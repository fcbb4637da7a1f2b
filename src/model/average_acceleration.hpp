// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Newmark's average-acceleration rule (beta = 1/4, gamma = 1/2: the paper's trapezoidal rule) for
/// M u'' + C u' + K u = f(t), one step of size dt from (u_k, v_k, a_k):
///   K_eff u_{k+1} = f_{k+1} + M w_k + C (2/dt u_k + v_k),   w_k = c_u u_k + c_v v_k + a_k,
///   K_eff = K + 2/dt C + c_u M,   c_u = 4/dt^2,   c_v = 4/dt,
///   a_{k+1} = c_u (u_{k+1} - u_k) - c_v v_k - a_k,   v_{k+1} = v_k + dt/2 (a_k + a_{k+1}).
/// The recurrence only: solving K_eff is the caller's (integrators::Trapezoid through its
/// effective-stiffness strategies, the POD training through one factor).
#include "model/second_order_system.hpp"

namespace roifem::model {

class AverageAcceleration {
 public:
  /// Throws InputError unless dt is positive and finite.
  explicit AverageAcceleration(double dt);
  double dt() const { return dt_; }
  double c_u() const { return 4.0 / (dt_ * dt_); }
  double c_v() const { return 4.0 / dt_; }

  /// c in K_eff = K + c M where C = alpha M: 4/dt^2 + 2 alpha/dt.
  double mass_factor(const Damping& damping) const { return c_u() + damping.alpha * 2.0 / dt_; }
  /// K + 2/dt C + 4/dt^2 M.
  SparseMatrix effective_stiffness(const SecondOrderSystem& system) const;
  /// The right-hand side as f + M w: with C = alpha M the damping history folds into w
  /// (w = (c_u + 2 alpha/dt) u + (c_v + alpha) v + a); a general C adds C (2/dt u + v) to f.
  void history(const SecondOrderSystem& system, const State& s, const Vector& a, Vector& f, Vector& w) const;
  /// From u_{k+1} (in u_next): a_{k+1} and v_{k+1}; u_{k+1} is swapped into s.u. `work` is scratch.
  void advance(State& s, Vector& a, Vector& u_next, Vector& work) const;
  /// The acceleration consistent with the equation at s: M a = f(s.t) - C v - K u.
  static Vector consistent_acceleration(const SecondOrderSystem& system, const State& s);

 private:
  double dt_;
};

}  // namespace roifem::model
