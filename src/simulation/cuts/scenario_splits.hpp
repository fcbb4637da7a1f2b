// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A scenario's cuts in split mode on its model: an incision that separates faces and removes no
/// material. The faces and the copies of the nodes they split are planned before the run
/// (cutting/split_plan.hpp); the copies are extra nodes of the model from the start, held at rest
/// with a stand-in mass and no stiffness, as a node a removal orphans is. A split at step k moves
/// corners of the tetrahedra around a node to its copy: K changes by sum_e (K_e on the new corners
/// - K_e on the old), the lumped mass rho V / 4 of those corners moves with them, the copy's stand-in
/// goes, and the copy starts where its node is, at its velocity. Displacements stay continuous, so
/// no strain or kinetic energy is taken (the event computes both from the state, as a check). As a
/// removal does, a split inside an ROI changes only K_dd, M_d and f_d: nothing is re-condensed.
#include <vector>

#include "cutting/node_splitter.hpp"
#include "cutting/split_plan.hpp"
#include "fem/material_map.hpp"
#include "model/fem_model.hpp"
#include "simulation/cuts/cut_event.hpp"

namespace roifem::simulation {

struct ScenarioModel;

class ScenarioSplits {
 public:
  /// The splits of `model` (built with its plan); `system_dof`: per free dof of the full model,
  /// its unknown in the integrated system; `gravity`: the load terms that are gravity, with g;
  /// `anchored`: per tetrahedron, whether its piece keeps a node that splits (cutting::NodeSplitter).
  ScenarioSplits(const ScenarioModel& model, std::vector<Index> system_dof, std::vector<std::pair<std::size_t, Vec3>> gravity,
                 double time_slack, std::vector<bool> anchored);
  bool due(double t) const { return next_ < plan_->faces.size() && plan_->faces[next_].time <= t + time_slack_; }
  /// Separates the faces due by t, splits what falls apart in `model` (its mesh's tetrahedra
  /// included) and sets each new copy's state to its node's. The integrator must then take
  /// event.change, unless it is empty (faces opened, no node split yet).
  CutEvent split_due(double t, ScenarioModel& model, model::State& state, const std::vector<bool>& supported);
  /// Faces separated so far.
  std::size_t faces_separated() const { return next_; }

 private:
  const cutting::SplitPlan* plan_;
  cutting::NodeSplitter splitter_;
  std::vector<double> stand_in_;  ///< per copy
  std::vector<Index> system_dof_;
  std::vector<std::pair<std::size_t, Vec3>> gravity_;
  double time_slack_;
  std::size_t next_ = 0;
};

}  // namespace roifem::simulation
