// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/average_acceleration.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "model/internal_force.hpp"
#include "model/time_grid.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::model {

AverageAcceleration::AverageAcceleration(double dt) : dt_(dt) { check_time_step(dt, "trapezoid"); }

SparseMatrix AverageAcceleration::effective_stiffness(const SecondOrderSystem& system) const {
  return system.K + (2.0 / dt_) * system.C + c_u() * system.M;
}

void AverageAcceleration::history(const SecondOrderSystem& system, const State& s, const Vector& a, Vector& f, Vector& w) const {
  const Damping& damping = system.damping;
  if (damping.is_mass_proportional()) {
    w = mass_factor(damping) * s.u + (c_v() + damping.alpha) * s.v + a;
  } else {
    w = (2.0 / dt_) * s.u + s.v;
    f.noalias() += system.C * w;
    w = c_u() * s.u + c_v() * s.v + a;
  }
}

void AverageAcceleration::advance(State& s, Vector& a, Vector& u_next, Vector& work) const {
  work = c_u() * (u_next - s.u) - c_v() * s.v - a;
  s.v += 0.5 * dt_ * (a + work);
  a.swap(work);
  s.u = u_next;  // a copy, not a swap: the state's storage is the caller's (integrator.hpp)
}

Vector AverageAcceleration::consistent_acceleration(const SecondOrderSystem& system, const State& s) {
  Vector r = system.load.at(s.t) - system.C * s.v;
  if (system.internal_force) {
    Vector f_int(s.u.size());
    system.internal_force->force(s.t, s.u, f_int);
    r -= f_int;
  } else {
    r -= system.K * s.u;
  }
  solvers::Cholesky mass;
  mass.compute(system.M);
  return mass.solve(r);
}

}  // namespace roifem::model
