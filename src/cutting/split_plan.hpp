// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What a run's blades in split mode will do, found before the run: the faces they separate within
/// it (cutting/separated_faces.hpp) and, from a dry run of the node splitting (node_splitter.hpp),
/// the copies each node needs. The copies are reserved up front as extra nodes of the mesh, at
/// their originals' positions, so that a split changes the model's operators on a fixed set of
/// unknowns: the trapezoidal rule's factor takes it as a low-rank change, as it takes a removal.
#include <vector>

#include "common/types.hpp"
#include "cutting/blade.hpp"
#include "cutting/node_splitter.hpp"
#include "cutting/separated_faces.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::cutting {

struct SplitPlan {
  std::vector<SeparatedFace> faces;              ///< each face once, at the earliest time, ascending
  std::vector<const Blade*> blade_of;            ///< per face, the blade that separates it first
  std::vector<std::array<Index, 4>> neighbours;  ///< the mesh's face neighbours
  Index num_nodes = 0;                           ///< the mesh's own nodes; copies come after
  std::vector<std::vector<int>> copies;          ///< per node, the copies reserved for it (node numbers)
  std::vector<int> copy_of;                      ///< per copy (node num_nodes + k), its original
  Index num_copies() const { return static_cast<Index>(copy_of.size()); }
};

/// The plan for `blades` (those in split mode) on `mesh` over a run ending at t_end (faces the
/// blades reach later are left out). InputError naming the blade for one that separates no face
/// of the mesh within the run.
SplitPlan plan_splits(const std::vector<Blade>& blades, const mesh::TetMesh& mesh, double t_end);

/// What the run will move, face by face in the plan's order with `anchored` (NodeSplitter): each
/// move with the face that causes it (an index into plan.faces). A move's `from` and `to` are the
/// rehearsal's numbers; its element's corner in `tets` names the original node.
std::vector<std::pair<Rewire, std::size_t>> rehearse(const SplitPlan& plan, const std::vector<mesh::Tet>& tets,
                                                     const std::vector<bool>& anchored);

/// The mesh with the plan's copies appended as nodes (at their originals' positions, in no
/// tetrahedron yet).
mesh::TetMesh with_copies(mesh::TetMesh mesh, const SplitPlan& plan);

}  // namespace roifem::cutting
