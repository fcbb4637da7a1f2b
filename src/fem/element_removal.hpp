// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What removing tetrahedra (a cut in remove mode) does to the trapezoidal rule's effective
/// stiffness K_eff = K + c M (c = 4/dt^2 + 2 alpha/dt, the lumped M: integrators/trapezoid.hpp),
/// over the free dofs of a DofMap, as a change for solvers::LowRankUpdate:
///   dK_eff = -sum_e A_e^T (K_e + c M_e) A_e,
/// K_e the linear tet4's stiffness (fem/tet4.hpp), M_e = rho V / 4 on each of its nodes, A_e its
/// free dofs. A node left with no element has no stiffness and no mass: its dofs get a pin, the
/// change c m_i (its old mass term) on their diagonal, so that the matrix stays nonsingular and
/// those dofs keep what the right-hand side gives them (an integrator holds them at rest).
/// The matrix rebuilt from the cut mesh with the same pins is the same matrix (the tests check it).
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

struct ElementRemoval {
  std::vector<Index> dofs;        ///< the free dofs the removed elements touch, ascending
  DenseMatrix change;             ///< dK_eff on them (symmetric), the orphans' pins included
  Vector mass_change;             ///< per entry of dofs: the lumped mass removed there (kg, <= 0)
  std::vector<int> orphan_nodes;  ///< nodes left with no element, ascending
};

/// `removed`: tetrahedra of a linear mesh (distinct), `still_there[e]`: whether element e is in the
/// mesh before this removal (earlier cuts removed the others; empty: all are). Throws InputError
/// for an element out of range, removed twice or already gone, or a quadratic mesh.
ElementRemoval element_removal(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                               const std::vector<Index>& removed, double c, const std::vector<bool>& still_there = {});

/// The mesh as cuts leave it: which tetrahedra remain and how many meet at each node, so that a
/// removal costs its own elements (element_removal scans the whole mesh for the nodes it orphans).
/// The mesh, dofs and materials must outlive it.
class ElementRemover {
 public:
  ElementRemover(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials);
  /// Removes `removed` (distinct, still there) and returns the change, as element_removal does;
  /// InputError as it does, nothing removed then.
  ElementRemoval remove(const std::vector<Index>& removed, double c);
  const std::vector<bool>& still_there() const { return alive_; }

 private:
  const mesh::TetMesh* mesh_;
  const DofMap* dofs_;
  const MaterialMap* materials_;
  std::vector<bool> alive_;
  std::vector<int> elements_at_;  ///< per node, the tetrahedra still there that hold it
};

}  // namespace roifem::fem
