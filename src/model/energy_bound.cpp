// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/energy_bound.hpp"

#include <algorithm>
#include <cmath>

#include "model/internal_force.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::model {

namespace {

/// max_t |r(t)|: 1 for a linear or smooth rise (monotone from 0 to 1), the largest sample otherwise.
double largest_value(const Ramp& ramp) {
  if (ramp.shape != Ramp::Shape::sampled) return 1.0;
  double largest = 0;
  for (const double r : ramp.samples->value) largest = std::max(largest, std::abs(r));
  return largest;
}

}  // namespace

EnergyBound::EnergyBound(const SecondOrderSystem& system, const State& initial)
    : system_(&system), t0_(initial.t), work_(system.size()) {
  if (system.M_split.empty() && is_diagonal(system.M)) mass_diagonal_ = system.M.diagonal();
  const MassInverse M_inverse(system.M);
  Vector x(system.size());
  for (const auto& term : system.load.terms()) {
    M_inverse.apply(term.pattern, x);
    rate_ += std::sqrt(std::max(0.0, term.pattern.dot(x))) * largest_value(term.ramp);
  }
  // 2 E_strain: u^T K u, or a nonlinear system's 2 W(u) (the bound's argument holds for any W >= 0).
  double strain = 0;
  if (system.internal_force) {
    strain = std::max(0.0, 2 * system.internal_force->energy(initial.t, initial.u));
  } else {
    system.apply_stiffness(initial.u, work_);
    strain = std::max(0.0, initial.u.dot(work_));
  }
  const double kinetic = velocity_norm(initial);
  initial_ = std::sqrt(strain + kinetic * kinetic);
}

double EnergyBound::velocity_norm(const State& state) {
  double squared = 0;
  if (mass_diagonal_.size() > 0) {
    squared = state.v.cwiseAbs2().dot(mass_diagonal_);
  } else {
    system_->apply_mass(state.v, work_);
    squared = state.v.dot(work_);
  }
  return squared < 0 ? 0.0 : std::sqrt(squared);  // a round-off below zero of v^T M v; NaN stays NaN
}

}  // namespace roifem::model
