// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A change of a second-order system's operators on a few of its dofs, as a cut in remove mode
/// makes it (simulation/cuts/scenario_cuts.hpp): with U selecting the dofs,
///   K += U dK U^T,   M += U diag(dM) U^T,   C = alpha M follows,   p_k += U dp_k (each load term).
/// Dofs left with no element (`held`) have no stiffness and no load from then on; their lumped
/// mass stays in M as a stand-in so that M remains invertible for every method, and the caller
/// sets their velocity to zero: they stay at rest, carrying no energy (the mass they had is counted
/// removed). The trapezoidal rule's K_eff = K + c M changes by dK + c diag(dM) (effective()).
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/element_removal.hpp"
#include "model/second_order_system.hpp"

namespace roifem::model {

struct SystemChange {
  std::vector<Index> dofs;    ///< ascending, in the system's numbering
  DenseMatrix stiffness;      ///< dK on dofs (symmetric)
  Vector mass;                ///< dM on dofs (<= 0; zero at held dofs)
  std::vector<Vector> loads;  ///< per load term of the system, the change of its pattern on dofs
  std::vector<Index> held;    ///< dofs left with no element, ascending (a subset of dofs)
  /// dofs the change sets moving, ascending (a subset of dofs): at rest with no stiffness and no
  /// load before it, their u and v set with it (a split's copies, which take their node's)
  std::vector<Index> started;

  /// What removing tetrahedra makes of a system (`removal` formed with c = 0: dK alone, no pins):
  /// its dofs renumbered by `system_dof` (per free dof of `dofs`, the system's unknown; each
  /// removal dof must have one), its orphans' dofs held (their mass change zero), `load_terms` empty
  /// load changes (the caller adds gravity's).
  static SystemChange from_removal(const fem::ElementRemoval& removal, const fem::DofMap& dofs,
                                   const std::vector<Index>& system_dof, std::size_t load_terms);
  /// The change of K + c M: dK + c diag(dM).
  DenseMatrix effective(double c) const;
  /// Applies it in place: K (and K_split's sparse part), M (and M_split's sparse part), C by
  /// alpha dM, the load patterns; at held dofs K's rows and columns become exactly zero (dK is
  /// adjusted to the entries K holds, so that effective() stays the change K sees). Throws
  /// InputError when C is not mass-proportional or a load term is missing.
  void apply(SecondOrderSystem& system);
};

}  // namespace roifem::model
