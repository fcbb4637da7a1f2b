#pragma once
/// Energy bookkeeping along a trajectory, observed from outside the integrator:
///   E = v^T M v / 2 + u^T K u / 2,
///   W += (u_{n+1} - u_n)^T (f_n + f_{n+1}) / 2              (external work),
///   D += dt v_mid^T C v_mid,  v_mid = (v_n + v_{n+1}) / 2    (dissipated).
/// For the trapezoidal rule E_n + D_n - W_n = E_0 holds exactly (to round-off): multiply the
/// averaged equation of motion by u_{n+1} - u_n = dt v_mid.
#include "model/second_order_system.hpp"

namespace roifem::model {

class EnergyLedger {
 public:
  EnergyLedger(const SecondOrderSystem& system, const State& initial);
  /// Call with each new state, in order.
  void record(const State& next);
  double kinetic() const { return kinetic_; }
  double strain() const { return strain_; }
  double total() const { return kinetic_ + strain_; }
  double dissipated() const { return dissipated_; }
  double external_work() const { return work_; }
  /// E + D - W - E_0: zero for an exact discrete balance.
  double balance_residual() const { return total() + dissipated_ - work_ - initial_total_; }

 private:
  const SecondOrderSystem& system_;
  double alpha_;  ///< C = alpha M, or NaN
  State previous_;
  Vector f_previous_;
  Vector Mv_previous_, Mv_next_, Ku_;
  double kinetic_ = 0, strain_ = 0, dissipated_ = 0, work_ = 0, initial_total_ = 0;
};

}  // namespace roifem::model
