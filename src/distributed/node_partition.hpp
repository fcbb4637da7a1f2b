// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The free nodes of a mesh dealt to the ranks of a communicator. Every rank holds the whole mesh
/// (a 300k-node brain's is 40 MB), so every rank knows every node's number and may assemble any
/// element; the numbers are what the distributed matrices are indexed by. Rank r owns the
/// contiguous numbers [first[r], first[r + 1]); node n's dofs are 3 number[n] + c (c = x, y, z).
/// With more than one rank the nodes are dealt by PT-Scotch through PETSc's MatPartitioning on the
/// node graph (-mat_partitioning_type picks another), so that few element couplings cross ranks.
#include <petscmat.h>

#include <vector>

#include "fem/dof_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::distributed {

/// The node graph of a mesh: nodes sharing an element (CSR over all nodes, sorted, self excluded).
struct NodeGraph {
  std::vector<PetscInt> start, neighbours;
  static NodeGraph of(const mesh::TetMesh& mesh);
};

/// Each tetrahedron's nodes: its 4 corners, then on a quadratic mesh its 6 midpoints.
std::vector<int> element_nodes(const mesh::TetMesh& mesh, Index e);

struct NodePartition {
  std::vector<PetscInt> number;  ///< per mesh node: its free-node number, -1 when fixed
  std::vector<PetscInt> first;   ///< per rank r: the first number it owns; first[size] = count()
  std::vector<int> owned_nodes;  ///< this rank's mesh nodes in the order of their numbers
  int rank = 0;
  PetscInt count() const { return first.back(); }
  PetscInt owned_begin() const { return first[static_cast<std::size_t>(rank)]; }
  PetscInt owned_end() const { return first[static_cast<std::size_t>(rank) + 1]; }
  /// The rank that owns free-node number k.
  int owner(PetscInt k) const;
};

/// Partitions the free nodes of `dofs`. InputError unless every node is either wholly free or wholly
/// fixed (the distributed model keeps a node's three dofs together: block size 3).
NodePartition partition_free_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const NodeGraph& graph, MPI_Comm comm);

}  // namespace roifem::distributed
