// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Degrees of freedom and Dirichlet conditions by elimination. Node n has components 3n + c
/// (c = 0, 1, 2: x, y, z) in the "full" numbering; the unconstrained ones are numbered 0..#free-1
/// node by node, which keeps the three components of a node adjacent in every matrix.
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// Collects Dirichlet conditions before the numbering is fixed.
class Constraints {
 public:
  explicit Constraints(Index num_nodes);
  /// Prescribes component c (0..2) of node n to `value` (metres).
  void prescribe(Index node, int component, double value = 0.0);
  /// Prescribes all three components.
  void fix_node(Index node, const Vec3& value = Vec3::Zero());
  /// Fixes every node of a named set (throws InputError for a missing set).
  void fix_set(const mesh::TetMesh& mesh, const std::string& set_name);

  Index num_nodes() const { return static_cast<Index>(constrained_.size()) / 3; }
  bool is_constrained(Index full_dof) const { return constrained_[static_cast<std::size_t>(full_dof)]; }
  double value(Index full_dof) const { return value_[static_cast<std::size_t>(full_dof)]; }

 private:
  std::vector<bool> constrained_;
  std::vector<double> value_;
};

class DofMap {
 public:
  explicit DofMap(const Constraints& constraints);

  Index num_nodes() const { return static_cast<Index>(free_index_.size()) / 3; }
  Index num_full() const { return static_cast<Index>(free_index_.size()); }
  Index num_free() const { return static_cast<Index>(full_index_.size()); }
  Index num_constrained() const { return num_full() - num_free(); }
  /// Free index of (node, component), or -1 where it is constrained.
  int free_dof(Index node, int component) const { return free_index_[static_cast<std::size_t>(3 * node + component)]; }
  /// Full index 3n + c of free dof i.
  Index full_dof(Index free) const { return full_index_[static_cast<std::size_t>(free)]; }
  /// Prescribed values in the full numbering (zero at free dofs).
  const Vector& prescribed() const { return prescribed_; }

  /// Full 3N vector from free values plus the prescribed ones.
  Vector expand(const Eigen::Ref<const Vector>& u_free) const;
  /// Full 3N vector from free values, zero at constrained dofs (forces, velocities).
  Vector expand_homogeneous(const Eigen::Ref<const Vector>& u_free) const;
  /// Free part of a full 3N vector.
  Vector restrict_to_free(const Eigen::Ref<const Vector>& full) const;

 private:
  std::vector<int> free_index_;
  std::vector<Index> full_index_;
  Vector prescribed_;
};

}  // namespace roifem::fem
