// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The time levels t_k = t_0 + k dt that every fixed-step walker steps along (deal.II's
/// DiscreteTime): computed from k, never accumulated by t += dt, so that the same k gives the same
/// t in the run loop, the stepper, the trapezoidal rule and PETSc's TS. The one place a time step
/// is checked (positive and finite).
#include <string>
#include <string_view>

namespace roifem::model {

/// InputError "WHO: time step dt = X s must be positive" unless dt is positive and finite.
void check_time_step(double dt, std::string_view who);

class TimeGrid {
 public:
  TimeGrid(double t0, double dt, std::string_view who);
  double t0() const { return t0_; }
  double dt() const { return dt_; }
  double at(long k) const { return t0_ + static_cast<double>(k) * dt_; }
  /// The k with t_k = t (within 1e-9 of a step); InputError naming `who` and t when t is not a grid
  /// point, or lies before t_{from}.
  long index_of(double t, long from = 0) const;
  /// The last k with t_k <= t (within 1e-9 of a step).
  long last_at_or_before(double t) const;

 private:
  double t0_, dt_;
  std::string who_;
};

}  // namespace roifem::model
