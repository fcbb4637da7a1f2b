// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The internal force f_int(u) and tangent K_t(u) = df_int/du of hyperelastic tetrahedra
/// (fem/hyperelastic_element.hpp), each by its material's law (fem/hyperelastic_law.hpp), over the
/// free dofs of a DofMap:
///   f_int(u) = sum_e A_e^T f_e(u_e),   K_t(u) = sum_e A_e^T K_e(u_e) A_e,
/// at the full displacement u (3 per node, the prescribed values included, so a prescribed motion
/// strains the elements it touches as it does in the linear model's f_D = -K_fp u_p).
/// K_t has the linear stiffness's pattern (fem/assembly.hpp), whatever the subset of elements, so a
/// sparse factorization analysed once on K serves every K_t.
/// With the nodal-pressure element (fem/element.hpp), each tetrahedron keeps its law's deviatoric
/// part and the volumetric energy is taken at the nodes' averaged J over the whole mesh
/// (fem/nodal_volumetric_energy.hpp): the force at the free dofs is then every element's, whatever
/// the subset listed (which still names the elements whose deviatoric part counts), and K_t has the
/// linear nodal-pressure stiffness's pattern (nodes two elements apart).
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/element.hpp"
#include "fem/hyperelastic_element.hpp"
#include "fem/hyperelastic_law.hpp"
#include "fem/material_map.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/nodal_volumetric_energy.hpp"
#include "fem/tet4.hpp"
#include "fem/tet4_excess_batch.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

class HyperelasticAssembler {
 public:
  /// Every tetrahedron of `mesh` (tet4, or tet10 on a quadratic mesh), each with its material's
  /// law and moduli. Keeps references to mesh and dofs, which must outlive it (materials: a copy).
  HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials);
  /// Only the tetrahedra listed (the hybrid ROI's nonlinear elements).
  HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, std::vector<Index> elements);
  /// With `element` (tet4 or nodal-pressure on a linear mesh, tet10 on a quadratic one); the
  /// nodal-pressure element takes every tetrahedron's bulk modulus from its material's law.
  HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, std::vector<Index> elements,
                        Element element);

  /// f_int at the full displacement u_full (3N). Throws ModelError naming the first tetrahedron
  /// that has inverted (det F <= 0 at a quadrature point), with its nodes and det F.
  void force(const Vector& u_full, Eigen::Ref<Vector> f_int) const;
  /// What the law's force exceeds the linear elements' by, f_int(u) - K_lin u with K_lin the same
  /// elements' linear stiffness (the law's tangent at rest), element by element
  /// (fem/hyperelastic_element.hpp's Evaluate::excess): no product by K_lin. From the free
  /// displacement alone (the prescribed values the DofMap's); where every element is a neo-Hookean
  /// tet4, the inner loop is written for a haptic tick: eight elements at a time in vector
  /// instructions (fem/tet4_excess_batch.hpp; equal to the element-by-element excess to rounding).
  /// Inverted elements as in force().
  void excess_force_free(const Vector& u_free, Eigen::Ref<Vector> g) const;
  /// f_int and K_t at u_full; K_t's values are overwritten in pattern()'s pattern.
  void force_and_tangent(const Vector& u_full, Eigen::Ref<Vector> f_int, SparseMatrix& K_t) const;
  /// Gonzalez's algorithmic force between the full displacements u_a and u_b
  /// (fem/discrete_gradient.hpp): f_alg . (u_b - u_a) = energy(u_b) - energy(u_a) over the free
  /// dofs, when the prescribed values are the same in both. An inverted element as in force().
  /// InputError with the nodal-pressure element, whose nodal energy has no discrete gradient here.
  void discrete_gradient(const Vector& u_a_full, const Vector& u_b_full, Eigen::Ref<Vector> f_alg) const;
  /// The same and K_alg = df_alg/du_b (not symmetric), in pattern()'s pattern as force_and_tangent.
  void discrete_gradient_and_tangent(const Vector& u_a_full, const Vector& u_b_full, Eigen::Ref<Vector> f_alg,
                                     SparseMatrix& K_alg) const;
  /// Whether discrete_gradient is formed: not with the nodal-pressure element.
  bool has_discrete_gradient() const { return nodal_ == nullptr; }
  /// The strain energy sum_e int W(F) dV (J).
  double energy(const Vector& u_full) const;
  /// The pattern of K_t (the linear K_ff's), values zero.
  const SparseMatrix& pattern() const { return pattern_; }
  const std::vector<Index>& elements() const { return elements_; }

 private:
  template <class Evaluator, class Visit>
  void for_each_element(Evaluator&& evaluate, Visit&& visit) const;
  template <class Visit>
  void for_each_element(const Vector& u_full, Evaluate what, Visit&& visit) const;
  /// f = the elements' forces (force or excess) at u_full, over the free dofs.
  void add_forces(const Vector& u_full, Evaluate what, Eigen::Ref<Vector> f) const;
  void discrete_gradient(const Vector& u_a_full, const Vector& u_b_full, Eigen::Ref<Vector> f_alg, SparseMatrix* K_alg) const;
  void check_size(const Vector& u_full) const;
  /// The nodes of the `slot`-th element listed (corners, then midpoints on a quadratic mesh).
  std::span<const int> nodes_of(std::size_t slot, std::array<int, 10>& nodes) const;
  /// Where each entry of an element's matrix lands among the pattern's values (-1: a constrained
  /// row or column), column by column: built once when it fits the budget below.
  void cache_positions();
  /// Adds the `slot`-th element's matrix into K at its free dofs.
  void scatter(std::size_t slot, std::span<const int> nodes, const Eigen::Ref<const DenseMatrix>& K_e, SparseMatrix& K) const;

  const mesh::TetMesh& mesh_;
  const DofMap& dofs_;
  MaterialMap materials_;
  std::vector<Index> elements_;
  SparseMatrix pattern_;
  /// Per element, its matrix's (3 n)^2 positions (cache_positions); empty where they would pass
  /// 32M entries (128 MB: the 20k-node brain's tet4 take 16M), and scatter() then searches.
  std::vector<int> positions_;
  /// Per element of a linear mesh, its geometry, formed once (a haptic tick evaluates the force
  /// several times a millisecond): 104 bytes an element.
  std::vector<Tet4Geometry> tet4_geometry_;
  /// The law of each of materials_'s materials, and per element which it takes.
  std::vector<HyperelasticLaw> laws_;
  std::vector<std::uint16_t> law_of_;
  /// A linear mesh's elements, kTet4Lanes at a time, for excess_force_free: their geometry and law
  /// lane by lane, and each dof's free row (-1: prescribed or no element) and full index (-1: no
  /// element).
  struct ExcessBatch {
    Tet4ExcessBatch law;
    int rows[12][kTet4Lanes];
    int full[12][kTet4Lanes];
  };
  std::vector<ExcessBatch> excess_batches_;
  void batch_excess();
  /// The nodal-pressure element's volumetric energy (null for tet4 and tet10).
  std::shared_ptr<const NodalVolumetricEnergy> nodal_;
};

}  // namespace roifem::fem
