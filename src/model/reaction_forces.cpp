// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/reaction_forces.hpp"

#include "fem/dof_map.hpp"
#include "fem/element.hpp"

namespace roifem::model {

ReactionForces::ReactionForces(const FemModel& model) {
  const mesh::TetMesh& mesh = *model.mesh;
  // Fixed by the boundary: constrained before the tools were (their map, when there are tools).
  const fem::DofMap& fixed = model.dofs_with_tools ? *model.dofs_with_tools : *model.dofs;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (fixed.free_dof(n, 0) < 0) nodes_.push_back(static_cast<int>(n));
  // K over every dof: a dof map with nothing constrained.
  const fem::DofMap every(fem::Constraints{mesh.num_nodes()});
  const SparseMatrix K = fem::stiffness(mesh, every, model.materials, model.element);
  std::vector<Eigen::Triplet<double>> pick;
  pick.reserve(3 * nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    for (int c = 0; c < 3; ++c) pick.emplace_back(static_cast<Index>(3 * i) + c, 3 * Index{nodes_[i]} + c, 1.0);
  SparseMatrix P(static_cast<Index>(3 * nodes_.size()), K.rows());
  P.setFromTriplets(pick.begin(), pick.end());
  rows_ = P * K;
}

Vector ReactionForces::nodal(const Eigen::Ref<const Vector>& u_all) const { return rows_ * u_all; }

Vec3 ReactionForces::total(const Eigen::Ref<const Vector>& u_all) const {
  const Vector r = nodal(u_all);
  return r.reshaped(3, r.size() / 3).rowwise().sum();
}

}  // namespace roifem::model
