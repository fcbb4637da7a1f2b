#include "model/energy.hpp"

namespace roifem::model {

EnergyLedger::EnergyLedger(const SecondOrderSystem& system, const State& initial)
    : system_(system), previous_(initial), f_previous_(system.load.at(initial.t)) {
  kinetic_ = kinetic_energy(system, initial);
  strain_ = strain_energy(system, initial);
  initial_total_ = total();
}

void EnergyLedger::record(const State& next) {
  const Vector f_next = system_.load.at(next.t);
  const double dt = next.t - previous_.t;
  const Vector v_mid = 0.5 * (previous_.v + next.v);
  work_ += 0.5 * (next.u - previous_.u).dot(f_previous_ + f_next);
  dissipated_ += dt * v_mid.dot(system_.C * v_mid);
  kinetic_ = kinetic_energy(system_, next);
  strain_ = strain_energy(system_, next);
  previous_ = next;
  f_previous_ = f_next;
}

}  // namespace roifem::model
