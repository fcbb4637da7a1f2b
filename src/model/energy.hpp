// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Energy bookkeeping along a trajectory, observed from outside the integrator:
///   E = v^T M v / 2 + u^T K u / 2,
///   W += (u_{n+1} - u_n)^T (f_n + f_{n+1}) / 2              (external work),
///   D += dt v_mid^T C v_mid,  v_mid = (v_n + v_{n+1}) / 2    (dissipated).
/// For the trapezoidal rule E_n + D_n - W_n = E_0 holds exactly (to round-off): multiply the
/// averaged equation of motion by u_{n+1} - u_n = dt v_mid.
/// With tools (tools.hpp, eliminated from the system), E also holds the coupling energy, W only the
/// loads' work (on the tissue and on the tools' nodes), and the tools' work is kept apart,
///   W_tools += (g_{n+1} - g_n) . (F_n + F_{n+1}) / 2,
/// so that E + D = E_0 + W + W_tools, again exactly for the trapezoidal rule. A nonlinear system's
/// strain energy is its W(t, u) (model/internal_force.hpp), the same ledger then holding to the
/// rule's O(dt^2) error.
/// A cut (simulation/cuts/scenario_cuts.hpp) changes the system in place between two states: the
/// energy its removed elements and mass carried is booked as E_cut (account_cut), and from then
/// on E + D + E_cut = E_0 + W + W_tools, again exactly for the trapezoidal rule.
#include <vector>

#include "model/second_order_system.hpp"
#include "model/tools.hpp"

namespace roifem::model {

class EnergyLedger {
 public:
  /// `tools`: the system's tools, or none; kept by pointer.
  EnergyLedger(const SecondOrderSystem& system, const State& initial, const ToolSet* tools = nullptr);
  /// Call with each new state, in order.
  void record(const State& next);
  double kinetic() const { return kinetic_; }
  double strain() const { return strain_ + coupling_; }
  double total() const { return kinetic_ + strain(); }
  double dissipated() const { return dissipated_; }
  /// The loads' work.
  double external_work() const { return work_ + load_work_at_tools_; }
  double tool_work() const { return tool_work_; }
  /// The tools' forces F at the last state recorded (or the initial one): 3 per tool.
  const Vector& tool_forces() const { return tools_previous_.forces; }
  /// E + D - W - W_tools - E_0: zero for an exact discrete balance.
  double balance_residual() const { return total() + dissipated_ + cut_ - external_work() - tool_work_ - initial_total_; }
  /// The system has been changed in place (a cut) at `state` (the last recorded one, its held
  /// dofs' velocity zeroed), taking `energy_removed` (J) with what it removed: E is re-read from
  /// the changed system and E_cut grows by energy_removed; the balance then says whether the two agree.
  void account_cut(const State& state, double energy_removed);
  /// E_cut: the energy the cuts took away (J).
  double cut() const { return cut_; }
  /// Its running sums (dissipation, the loads' and tools' work, E_0, E_cut, ...), for a restart.
  std::vector<double> sums() const;
  /// Goes on from `state` with the sums() a ledger had there, as that ledger would: what it keeps
  /// of the state (M v, the load, the tools' terms) is computed from it as record() computed it.
  void resume(const State& state, const std::vector<double>& sums);

 private:
  /// The tools' terms of a state: positions g, coupling u, loads on their nodes, forces F.
  struct ToolTerms {
    Vector g, coupled, loads, forces;
    double coupling_energy = 0;
  };
  ToolTerms tool_terms(const State& s) const;
  /// The strain energy u^T K u / 2, or a nonlinear system's W(t, u).
  /// E of state s from the system as it is now (M v kept as the previous state's).
  void read_energies(const State& s);
  double strain(double t, const Vector& u);

  const SecondOrderSystem& system_;
  const ToolSet* tools_;  ///< null or empty: none
  double alpha_;          ///< C = alpha M, or NaN
  State previous_;
  Vector f_previous_;
  Vector Mv_previous_, Mv_next_, Ku_;
  ToolTerms tools_previous_;
  double kinetic_ = 0, strain_ = 0, dissipated_ = 0, work_ = 0, initial_total_ = 0;
  double coupling_ = 0, tool_work_ = 0, cut_ = 0;
  /// The loads' work as the system sees it (work_) counts -K_fp G as a load: this corrects it to
  /// the loads' own work, and adds theirs on the tools' nodes.
  double load_work_at_tools_ = 0;
};

}  // namespace roifem::model
