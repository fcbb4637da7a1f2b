// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/reaction_forces.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "fem/dof_map.hpp"
#include "fem/element.hpp"
#include "fem/tet4.hpp"

namespace roifem::model {

namespace {

/// The rows of K at `nodes` over every dof, from the linear tetrahedra `still_there` marks.
SparseMatrix rows_of_the_tetrahedra_left(const FemModel& model, const std::vector<int>& nodes,
                                         const std::vector<bool>& still_there) {
  const mesh::TetMesh& mesh = *model.mesh;
  if (model.element != fem::Element::tet4) throw Error("internal: reactions after a removal need linear tetrahedra");
  std::vector<Index> row(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) row[static_cast<std::size_t>(nodes[i])] = 3 * static_cast<Index>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const mesh::Tet& tet = mesh.tets[static_cast<std::size_t>(e)];
    if (!still_there[static_cast<std::size_t>(e)] ||
        std::none_of(tet.begin(), tet.end(), [&](int n) { return row[static_cast<std::size_t>(n)] >= 0; }))
      continue;
    const fem::ElementMatrix K = fem::tet4_stiffness(
        fem::tet4_geometry(mesh.node(tet[0]), mesh.node(tet[1]), mesh.node(tet[2]), mesh.node(tet[3])), model.materials.of(e));
    for (int a = 0; a < 12; ++a) {
      const Index r = row[static_cast<std::size_t>(tet[static_cast<std::size_t>(a / 3)])];
      if (r < 0) continue;
      for (int b = 0; b < 12; ++b)
        entries.emplace_back(r + a % 3, 3 * Index{tet[static_cast<std::size_t>(b / 3)]} + b % 3, K(a, b));
    }
  }
  SparseMatrix rows(static_cast<Index>(3 * nodes.size()), 3 * mesh.num_nodes());
  rows.setFromTriplets(entries.begin(), entries.end());
  return rows;
}

}  // namespace

ReactionForces::ReactionForces(const FemModel& model, const std::vector<bool>& still_there) {
  const mesh::TetMesh& mesh = *model.mesh;
  // Fixed by the boundary: constrained before the tools were (their map, when there are tools).
  const fem::DofMap& fixed = model.dofs_with_tools ? *model.dofs_with_tools : *model.dofs;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (fixed.free_dof(n, 0) < 0) nodes_.push_back(static_cast<int>(n));
  if (std::find(still_there.begin(), still_there.end(), false) != still_there.end()) {
    rows_ = rows_of_the_tetrahedra_left(model, nodes_, still_there);
    return;
  }
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
