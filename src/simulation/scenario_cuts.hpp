// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A scenario's cuts ([[cut]], remove mode) on its model: which tetrahedra the blades cross and
/// when (cutting/blade.hpp), and at each step the change removing the due ones makes to the
/// integrated system (model/system_change.hpp), in place. Inside an ROI only the condensed
/// operators' ROI part changes (K_dd, the lumped M, f_d): the static part, its factor and the
/// interface Schur block stay exactly as they were, which is why a cut needs no re-condensation.
///
/// What is refused, before any step (InputError naming the cut, the tetrahedron, the node and the
/// time): a blade that meets no tetrahedron, or none before the run ends; a tetrahedron at a node of
/// the static part (the ROI must hold the cut: a larger [roi]) or at a tool's node; a cut that
/// removes every tetrahedron of the ROI (or of the mesh); a cut on a nonlinear material, on
/// tet10 or nodal-pressure elements, on a reduction by modes (Craig-Bampton's and POD's bases
/// belong to the uncut mesh) or with a DAE form (its constrained system is the uncut one).
/// A piece cut loose from every support is not refused: with the lumped mass it moves rigidly
/// under its loads (K singular there, K + c M not), and the event's warnings name it and its nodes.
#include <string>
#include <vector>

#include <optional>

#include "cutting/blade.hpp"
#include "fem/element_removal.hpp"
#include "model/system_change.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

/// What one step's removal did.
struct CutEvent {
  double time = 0;                    ///< s: the state's time when it took effect (the start of the step that reaches them)
  std::vector<Index> elements;        ///< tetrahedra removed, ascending
  std::vector<int> orphan_nodes;      ///< nodes left with no element: held at rest from now on
  model::SystemChange change;         ///< in the integrated system's numbering
  double strain_energy = 0;           ///< J: what the removed tetrahedra stored, u_e^T K_e u_e / 2 summed
  double kinetic_energy = 0;          ///< J: what the removed mass carried, sum dm_i |v_i|^2 / 2
  double mass_removed = 0;            ///< kg: rho V of the removed tetrahedra
  std::vector<std::string> warnings;  ///< pieces cut loose, loads on nodes left with no element
  double energy_removed() const { return strain_energy + kinetic_energy; }
};

class ScenarioCuts {
 public:
  /// The blades of `scenario` on `model` (built from it); the refusals above.
  ScenarioCuts() = default;
  ScenarioCuts(const scenario::Scenario& scenario, const ScenarioModel& model);
  bool empty() const { return schedule_.empty(); }
  /// Whether tetrahedra are due by time t that are not yet removed.
  bool due(double t) const { return next_ < schedule_.size() && schedule_[next_].time <= t + time_slack_; }
  /// Removes the tetrahedra due by t from `model`'s integrated system at `state` (whose velocity it
  /// sets to zero at the held dofs). The integrator must then take event.change (Integrator::take_change).
  CutEvent remove_due(double t, ScenarioModel& model, model::State& state);
  /// The tetrahedra the blades cross within the run, with the time each is reached, ascending.
  const std::vector<cutting::Crossing>& schedule() const { return schedule_; }
  /// Per tetrahedron, whether it is still in the mesh (empty without cuts).
  const std::vector<bool>& still_there() const { return remover_ ? remover_->still_there() : no_cuts_; }

 private:
  std::vector<cutting::Crossing> schedule_;
  std::size_t next_ = 0;
  double time_slack_ = 0;                       ///< 1e-9 dt: a blade reaching a tetrahedron at t_k is due at t_k
  std::optional<fem::ElementRemover> remover_;  ///< the mesh as the cuts leave it
  std::vector<bool> no_cuts_;
  std::vector<Index> system_dof_;  ///< per free dof of the full model: its unknown in the system (-1: static part)
  std::vector<std::pair<std::size_t, Vec3>> gravity_;  ///< load terms that are gravity, and g
  std::vector<bool> supported_;                        ///< per node: fixed, held by a tool or in the static part
};

}  // namespace roifem::simulation
