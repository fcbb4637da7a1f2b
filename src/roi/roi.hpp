// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The region of interest (ROI) and the split of the free dofs it induces:
///   d  ROI dofs (dynamic),  s  static dofs (the rest),
///   interface: the ROI dofs coupled to static dofs through K (K_sd has non-zeros only there).
/// A node is in the ROI as a whole; fixed components of a node are in neither d nor s.
#include <string>
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::roi {

struct RoiSpec {
  enum class Kind { all, ball, nearest, set };
  Kind kind = Kind::all;
  Vec3 center = Vec3::Zero();  ///< m (ball centre, or the target point of `nearest`)
  double radius = 0;           ///< m (ball)
  Index count = 0;             ///< nodes (nearest)
  std::string set;             ///< named set (set)
  std::string describe() const;
};

/// The nodes with at least one free component, ascending.
std::vector<int> free_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs);

/// The ROI's nodes (sorted), among nodes with at least one free dof. ModelError for an empty
/// ROI (naming the spec), a count larger than the free nodes, or a `nearest` target outside the
/// mesh's bounding box.
std::vector<int> select_roi_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const RoiSpec& spec);

struct Partition {
  std::vector<int> roi_nodes;    ///< sorted
  std::vector<Index> d;          ///< free dof indices of the ROI, ascending
  std::vector<Index> s;          ///< free dof indices of the static part, ascending
  std::vector<Index> interface;  ///< positions in d (0..#d-1) of dofs coupled to s, ascending
  Index roi_size() const { return static_cast<Index>(d.size()); }
  Index static_size() const { return static_cast<Index>(s.size()); }
};

/// Splits the free dofs of K by the ROI nodes.
Partition partition_dofs(const SparseMatrix& K, const fem::DofMap& dofs, const std::vector<int>& roi_nodes);

/// K(rows, cols) for index lists (ascending).
SparseMatrix submatrix(const SparseMatrix& K, const std::vector<Index>& rows, const std::vector<Index>& cols);
/// v(indices).
Vector gather(const Vector& v, const std::vector<Index>& indices);

}  // namespace roifem::roi
