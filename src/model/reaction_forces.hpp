// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The supports' reactions: the force the support of each fixed node exerts on the tissue,
///   R_i = (K u)_i   at the fixed dofs i,
/// with K assembled over every dof (the model's K_ff lacks the fixed rows) and u the whole
/// displacement (3N: free values, tools' paths, zeros at the fixed nodes). The equation of motion
/// of a fixed node has no inertia or damping (it does not move; M is lumped), so this is the whole
/// reaction. A load that the scenario puts on a fixed node (FemModel warns of it) goes straight into
/// the support and is not counted here. In static equilibrium sum R = -sum f and sum x x R = -sum
/// x x f: K annihilates rigid motions (tests/model/reaction_forces_test.cpp).
#include <vector>

#include "model/fem_model.hpp"

namespace roifem::model {

class ReactionForces {
 public:
  /// Assembles K over every dof and keeps the fixed nodes' rows of it (nothing of the model).
  /// After cuts: over the mesh's tetrahedra as they are now (a split rewires them in place) and,
  /// where `still_there` is given, only those it marks (a removal); cuts take linear tetrahedra.
  explicit ReactionForces(const FemModel& model, const std::vector<bool>& still_there = {});
  /// The fixed nodes (the fixed sets' nodes; tools' nodes are not among them), ascending.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Each fixed node's reaction (N), 3 per node in the order of nodes(), from the 3N displacement.
  Vector nodal(const Eigen::Ref<const Vector>& u_all) const;
  /// Their sum (N).
  Vec3 total(const Eigen::Ref<const Vector>& u_all) const;

 private:
  std::vector<int> nodes_;
  SparseMatrix rows_;  ///< 3 x #fixed nodes rows of K over all 3N dofs
};

}  // namespace roifem::model
