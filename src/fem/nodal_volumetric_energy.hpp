// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The volumetric part of the average-nodal-pressure tetrahedron at finite strain (Bonet & Burton
/// 1998; Bonet, Marriott & Hassan 2001; NiftySim's T4ANP): the laws' volumetric energy
/// kappa/2 (J - 1)^2 taken at the nodes' averaged J instead of each element's,
///   Pi_vol = sum_a V_a kappa_a / 2 (J_a - 1)^2,   J_a = v_a / V_a,
/// V_a = sum over a's elements of V_e / 4 (reference), v_a the same in the current configuration,
/// kappa_a = sum (V_e / 4) kappa_e / V_a, while each element keeps its law's deviatoric energy
/// (the law's deviatoric_part(): fem/hyperelastic_assembly.hpp). Its force and tangent are those of
/// an element pressure, the mean of its four nodes' pressures p_a = kappa_a (J_a - 1):
///   f   = sum_e V_e p_e cof(F_e) g,                                     p_e = sum_{a in e} p_a / 4,
///   K_t = sum_a V_a kappa_a G_a G_a^T + sum_e V_e p_e d^2 J_e / dx^2,  G_a = dJ_a/dx,
/// G_a spanning the nodes of a's elements (the pattern of nodes two elements apart, the linear
/// nodal-pressure stiffness's). At rest K_t is fem/nodal_pressure.hpp's volumetric part with s = 0,
/// so the element's small-strain limit is the linear nodal-pressure element, term for term.
/// J_e - 1 and cof(F) - I are formed from H without cancellation, so the excess over the linear
/// form keeps its digits at small strain, as the laws' excess stress does.
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

class NodalVolumetricEnergy {
 public:
  /// Every tetrahedron of a linear `mesh`, element e with bulk modulus element_kappa[e] (Pa).
  /// Keeps references to mesh and dofs, which must outlive it.
  NodalVolumetricEnergy(const mesh::TetMesh& mesh, const DofMap& dofs, std::vector<double> element_kappa);

  /// Pi_vol at the full displacement u_full (3N), J.
  double energy(const Vector& u_full) const;
  /// f += dPi_vol/du over the free dofs.
  void add_force(const Vector& u_full, Eigen::Ref<Vector> f) const;
  /// g += the force less its linearization at rest (the linear nodal-pressure element's volumetric
  /// K u), formed without cancellation.
  void add_excess_force(const Vector& u_full, Eigen::Ref<Vector> g) const;
  /// f += the force, K += the tangent, K's pattern containing pattern().
  void add_force_and_tangent(const Vector& u_full, Eigen::Ref<Vector> f, SparseMatrix& K) const;
  /// The tangent's pattern over the free dofs (values zero): nodes two elements apart.
  const SparseMatrix& pattern() const { return pattern_; }

 private:
  /// Per element, H = Grad u and J_e - 1; per node, J_a - 1 and kappa_a (J_a - 1).
  struct Strains {
    std::vector<Mat3> H;
    Vector J_minus_1;
    Vector nodal_J_minus_1;
    Vector nodal_pressure;
  };
  Strains strains(const Vector& u_full) const;
  /// The mean of element e's nodes' pressures.
  double element_pressure(const Strains& s, Index e) const;
  /// Adds the 12 entries of an element vector to f at the element's free dofs.
  void scatter(Index e, const Eigen::Matrix<double, 12, 1>& f_e, Eigen::Ref<Vector> f) const;
  void check_size(const Vector& u_full) const;

  const mesh::TetMesh& mesh_;
  const DofMap& dofs_;
  std::vector<Eigen::Matrix<double, 4, 3>> grad_;  ///< per element, row a = Grad N_a
  Vector volume_;                                  ///< per element, V_e
  Vector nodal_volume_;                            ///< V_a
  Vector nodal_kappa_;                             ///< kappa_a
  SparseMatrix pattern_;
  /// Each node's patch: the free dofs of its elements, ascending (patch_dofs_ from
  /// patch_begin_[a]), where G_a = dJ_a/dx lives; per element and corner, where each of its 12 dofs
  /// lies in that corner's patch (-1: constrained).
  std::vector<int> patch_begin_, patch_dofs_, element_local_;
  /// Per node, where its patch's m x m block lands among pattern()'s values (column by column, from
  /// block_begin_[a]); empty where it would pass 32M entries, and the tangent then searches.
  std::vector<std::size_t> block_begin_;
  std::vector<int> block_positions_;
  /// The value index of (patch row i, patch column j) of node a's block in K.
  int position(const SparseMatrix& K, bool cached, Index a, int i, int j) const;
};

}  // namespace roifem::fem
