// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Global matrices over the free dofs of a DofMap.
///  K:  stiffness, assembled directly into a compressed column pattern built once from the node
///      graph (no triplet list: a 100k-node brain would need 1.4 GB of triplets). Column by
///      column: node b gathers the blocks K_ab of its own tetrahedra, so every write lands in
///      b's few hundred contiguous values (scattering element by element missed cache on every
///      write and cost 14x the element matrices). Columns are independent, so OpenMP threads share
///      them without races, and each column sums in a fixed order: results do not depend on the
///      thread count.
///  M:  lumped mass, M_ii = sum over the node's tetrahedra of rho V / 4 (a diagonal, as a vector);
///      on a quadratic mesh HRZ's (fem/tet10.hpp): rho V/36 per corner, 4 rho V/27 per midpoint.
/// On a quadratic mesh (mesh/quadratic_mesh.hpp) K is the 10-node tetrahedron's.
///  f_D = -K_fp u_p: the load that prescribed (non-zero) Dirichlet values put on the free dofs.
#include <span>
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

class StiffnessAssembler {
 public:
  /// Builds the sparsity pattern (full symmetric storage, sorted columns). Keeps references:
  /// mesh and dofs must outlive the assembler.
  StiffnessAssembler(const mesh::TetMesh& mesh, const DofMap& dofs);

  /// K_ff for the material (each tetrahedron its own, from the map); same pattern on every call.
  SparseMatrix stiffness(const MaterialMap& materials) const;
  SparseMatrix stiffness(const Material& material) const { return stiffness(MaterialMap(material)); }
  /// -K_fp u_p: zero unless some prescribed value is non-zero.
  Vector prescribed_load(const MaterialMap& materials) const;
  Vector prescribed_load(const Material& material) const { return prescribed_load(MaterialMap(material)); }
  Index nonzeros() const { return static_cast<Index>(row_index_.size()); }

 private:
  const mesh::TetMesh& mesh_;
  const DofMap& dofs_;
  int nodes_per_tet_ = 4;           ///< 4, or 10 on a quadratic mesh
  std::vector<int> element_nodes_;  ///< per tetrahedron its nodes_per_tet_ nodes
  std::span<const int> nodes_of(Index e) const {
    return {element_nodes_.data() + e * nodes_per_tet_, static_cast<std::size_t>(nodes_per_tet_)};
  }
  std::vector<int> adjacency_start_, adjacency_;  ///< node graph (CSR, sorted, self included)
  std::vector<int> adjacency_offset_;             ///< free rows before adjacency entry k in its column
  std::vector<int> column_start_, row_index_;     ///< the CSC pattern of K_ff
  std::vector<int> tet_start_, tet_list_;         ///< node -> tetrahedra incidence (CSR)
};

/// Lumped mass per node, rho V / 4 from each tetrahedron (HRZ's on a quadratic mesh) (kg; rho: each tetrahedron's own).
Vector lumped_node_mass(const mesh::TetMesh& mesh, const MaterialMap& materials);
Vector lumped_node_mass(const mesh::TetMesh& mesh, double rho);
/// Lumped mass on the free dofs (the diagonal of M_ff).
Vector lumped_mass(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials);
Vector lumped_mass(const mesh::TetMesh& mesh, const DofMap& dofs, double rho);

}  // namespace roifem::fem
