// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/energy.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "model/internal_force.hpp"

namespace roifem::model {

EnergyLedger::ToolTerms EnergyLedger::tool_terms(const State& s) const {
  // One product with the coupling per state: F and the coupling energy both follow from it.
  ToolTerms terms{.g = tools_->positions(s.t), .coupled = tools_->coupling_times(s.u), .loads = tools_->loads_at_tools(s.t)};
  const Vector self_g = tools_->self_times(terms.g);
  terms.forces = tools_->forces(terms.coupled, self_g, s.u, s.t);
  terms.coupling_energy = terms.g.dot(terms.coupled) + 0.5 * terms.g.dot(self_g);
  return terms;
}

double EnergyLedger::strain(double t, const Vector& u) {
  if (system_.internal_force) return system_.internal_force->energy(t, u);  // W(t, u)
  system_.apply_stiffness(u, Ku_);
  return 0.5 * u.dot(Ku_);
}

EnergyLedger::EnergyLedger(const SecondOrderSystem& system, const State& initial, const ToolSet* tools)
    : system_(system),
      tools_(tools != nullptr && !tools->empty() ? tools : nullptr),
      alpha_(mass_proportional_damping(system)),
      previous_(initial),
      f_previous_(system.load.at(initial.t)),
      Mv_previous_(initial.v.size()),
      Mv_next_(initial.v.size()),
      Ku_(initial.u.size()) {
  read_energies(initial);
  initial_total_ = total();
}

void EnergyLedger::read_energies(const State& s) {
  system_.apply_mass(s.v, Mv_previous_);
  kinetic_ = 0.5 * s.v.dot(Mv_previous_);
  strain_ = strain(s.t, s.u);
  if (tools_ != nullptr) {
    tools_previous_ = tool_terms(s);
    coupling_ = tools_previous_.coupling_energy;
  }
}

void EnergyLedger::record(const State& next) {
  // One product with M and one with K per state (the split forms, where a reduced model keeps
  // dense blocks): M v_mid = (M v_n + M v_{n+1}) / 2 reuses the previous state's M v.
  const Vector f_next = system_.load.at(next.t);
  const double dt = next.t - previous_.t;
  const Vector v_mid = 0.5 * (previous_.v + next.v);
  work_ += 0.5 * (next.u - previous_.u).dot(f_previous_ + f_next);
  system_.apply_mass(next.v, Mv_next_);
  if (std::isfinite(alpha_))  // C = alpha M
    dissipated_ += dt * alpha_ * 0.5 * v_mid.dot(Mv_previous_ + Mv_next_);
  else
    dissipated_ += dt * v_mid.dot(system_.C * v_mid);
  kinetic_ = 0.5 * next.v.dot(Mv_next_);
  strain_ = strain(next.t, next.u);
  if (tools_ != nullptr) {
    ToolTerms now = tool_terms(next);
    const ToolTerms& was = tools_previous_;
    const Vector dg = now.g - was.g;
    load_work_at_tools_ += 0.5 * (now.g + was.g).dot(now.coupled - was.coupled) + 0.5 * dg.dot(now.loads + was.loads);
    tool_work_ += 0.5 * dg.dot(now.forces + was.forces);
    coupling_ = now.coupling_energy;
    tools_previous_ = std::move(now);
  }
  previous_ = next;
  f_previous_ = f_next;
  Mv_previous_.swap(Mv_next_);
}

std::vector<double> EnergyLedger::sums() const {
  return {kinetic_, strain_, dissipated_, work_, initial_total_, coupling_, tool_work_, cut_, load_work_at_tools_};
}

void EnergyLedger::resume(const State& state, const std::vector<double>& sums) {
  if (sums.size() != 9) throw InputError("a restart's energy sums: " + std::to_string(sums.size()) + " numbers, not 9");
  previous_ = state;
  f_previous_ = system_.load.at(state.t);
  system_.apply_mass(state.v, Mv_previous_);
  if (tools_ != nullptr) tools_previous_ = tool_terms(state);
  kinetic_ = sums[0];
  strain_ = sums[1];
  dissipated_ = sums[2];
  work_ = sums[3];
  initial_total_ = sums[4];
  coupling_ = sums[5];
  tool_work_ = sums[6];
  cut_ = sums[7];
  load_work_at_tools_ = sums[8];
}

void EnergyLedger::account_cut(const State& state, double energy_removed) {
  previous_ = state;
  f_previous_ = system_.load.at(state.t);
  read_energies(state);
  cut_ += energy_removed;
}

}  // namespace roifem::model
