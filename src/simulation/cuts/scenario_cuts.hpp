// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A scenario's cuts ([[cut]]) on its model. Remove mode: which tetrahedra the blades cross and
/// when (cutting/blade.hpp), and at each step the change removing the due ones makes to the
/// integrated system (model/system_change.hpp), in place. Split mode: the faces the blades
/// separate, the nodes that split (simulation/cuts/scenario_splits.hpp), and the change of each step. Inside an ROI only the
/// condensed operators' ROI part changes (K_dd, the lumped M, f_d): the static part, its factor and the interface Schur block
/// stay exactly as they were, which is why a cut needs no re-condensation.
///
/// What is refused, before any step (InputError naming the cut, the tetrahedron, the node and the
/// time): a blade that meets no tetrahedron, or none before the run ends; a tetrahedron at a node of
/// the static part (the ROI must hold the cut: a larger [roi]) or at a tool's node; a cut that
/// removes every tetrahedron of the ROI (or of the mesh); a split of a fixed node; a cut on a nonlinear material, on
/// tet10 or nodal-pressure elements, on a reduction by modes (Craig-Bampton's and POD's bases
/// belong to the uncut mesh) or with a DAE form (its constrained system is the uncut one).
/// A piece cut loose from every support is not refused: with the lumped mass it moves rigidly
/// under its loads (K singular there, K + c M not), and the event's warnings name it and its nodes.
#include <optional>
#include <string>
#include <vector>

#include "cutting/blade.hpp"
#include "fem/element_removal.hpp"
#include "model/system_change.hpp"
#include "scenario/scenario.hpp"
#include "simulation/cuts/cut_event.hpp"
#include "simulation/cuts/element_cuts.hpp"
#include "simulation/cuts/scenario_splits.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

class ScenarioCuts {
 public:
  /// The blades of `scenario` on `model` (built from it); the refusals above.
  ScenarioCuts() = default;
  ScenarioCuts(const scenario::Scenario& scenario, const ScenarioModel& model);
  bool empty() const { return schedule_.empty() && !splits_; }
  /// Whether tetrahedra (faces, in split mode) are due by time t that are not yet removed (separated).
  bool due(double t) const {
    return splits_ ? splits_->due(t) : next_ < schedule_.size() && schedule_[next_].time <= t + time_slack_;
  }
  /// Cuts what is due by t in `model`'s integrated system at `state`: removes the tetrahedra (and
  /// sets the velocity at the held dofs to zero), or separates the faces and splits the nodes (and
  /// starts each copy at its node's state). The integrator must then take event.change
  /// (Integrator::take_change) unless it is empty.
  CutEvent cut_due(double t, ScenarioModel& model, model::State& state);
  /// Remove mode: the tetrahedra the blades cross within the run, with the time each is reached, ascending.
  const std::vector<cutting::Crossing>& schedule() const { return schedule_; }
  /// Split mode: the run's plan (null in remove mode), and the faces separated so far.
  const cutting::SplitPlan* split_plan() const { return split_plan_; }
  std::size_t faces_separated() const { return splits_ ? splits_->faces_separated() : 0; }
  /// Split mode: the splits made so far (a node split twice counts twice).
  std::size_t nodes_split() const { return nodes_split_; }
  /// The tetrahedra's corners in the state at time t, the splits since undone (`mesh`: the model's, now).
  std::vector<mesh::Tet> tets_at(double t, const mesh::TetMesh& mesh) const;
  /// Per tetrahedron, whether it is still in the mesh (empty without cuts).
  const std::vector<bool>& still_there() const { return cutter_ && !splits_ ? cutter_->still_there() : no_cuts_; }

 private:
  CutEvent remove_due(double t, ScenarioModel& model, model::State& state);
  /// InputError for a split the run would make at a fixed node or a tool's, or moving a
  /// tetrahedron at the static part or a tool (rehearsed with `anchored`, as the run splits).
  void refuse_splits(const ScenarioModel& model, const std::vector<bool>& anchored) const;

  std::vector<cutting::Crossing> schedule_;
  std::size_t next_ = 0;
  const cutting::SplitPlan* split_plan_ = nullptr;
  std::optional<ScenarioSplits> splits_;
  std::vector<std::pair<double, cutting::Rewire>> moves_;
  std::size_t nodes_split_ = 0;        ///< split mode: each corner moved, and when
  double time_slack_ = 0;              ///< 1e-9 dt: a blade reaching a tetrahedron at t_k is due at t_k
  std::optional<ElementCuts> cutter_;  ///< the mesh as the cuts leave it, and what a removal changes
  std::vector<bool> no_cuts_;
};

}  // namespace roifem::simulation
