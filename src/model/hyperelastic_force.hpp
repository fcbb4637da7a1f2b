// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The internal force of a model whose elements follow the neo-Hookean law, all or some of them
/// (fem/hyperelastic_assembly.hpp), over its dofs:
///   f_int(u) = K_lin u + sum_{e nonlinear} A_e^T f_e(u_e),   K_t(u) = K_lin + sum_e A_e^T K_e(u_e) A_e,
/// where K_lin holds what stays linear:
///  - a full model: the elements of a linear material (none when every element is neo-Hookean);
///  - the hybrid ROI: the condensed K~ less the nonlinear elements' linear stiffness. Its nonlinear
///    elements are those with no node in the static part, so their linear stiffness lies wholly in
///    K_dd and condensation stays exact: K~ and f~ are the linear model's, and u_s is recovered
///    from u_d as before. With the ROI every free node, the hybrid is the full nonlinear model.
/// K_t is written in K_lin's pattern (the system's K), which contains the assembler's.
///
/// Tools (model/tools.hpp) whose nodes the law's elements hold move them along their paths g(t):
/// the elements read U = u (+) G(t). The system's load keeps the linear elimination's -K_up G(t),
/// so the force subtracts the elements' linear share of it, and the tools' forces gain what the
/// elements give beyond their linear stiffness there:
///   f_int(t, u) = K_lin u - K_ug g(t) + sum_e A_e^T f_e(U_e),
///   W(t, u)     = u^T K_lin u / 2 - u^T K_ug g - g^T K_gg g / 2 + sum_e W_e(U_e),
///   F_tool     += sum_e f_e(U_e) at the tool's nodes - K_ug^T u - K_gg g,
/// with K_ug, K_gg the law's elements' linear stiffness between the unknowns and the tools'
/// positions (3 per tool, summed over its nodes) and between the tools. Each is the linear model's
/// term plus what the law adds beyond linear, so a small motion gives the linear answer.
#include <memory>
#include <string>
#include <vector>

#include "fem/dof_map.hpp"
#include "fem/element.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "model/internal_force.hpp"
#include "model/second_order_system.hpp"
#include "model/tools.hpp"
#include "roi/roi.hpp"

namespace roifem::model {

class HyperelasticForce final : public InternalForce {
 public:
  /// The force of `elements` (their materials' law) over `dofs`, plus K_lin u; K_lin's pattern must
  /// contain the linear stiffness's over `dofs`. `dofs` is shared: the force may own it (the
  /// hybrid's) or borrow it (a FemModel's, through a non-owning pointer). `tools`: those whose
  /// nodes `dofs` holds (constrained), moving them along their paths.
  HyperelasticForce(std::shared_ptr<const fem::DofMap> dofs, const mesh::TetMesh& mesh, const fem::MaterialMap& materials,
                    fem::Element element, std::vector<Index> elements, const SparseMatrix& K_lin, bool K_lin_is_zero,
                    std::string description, std::vector<Tool> tools = {});
  /// Products with K_lin = K_split - K_elements through K_split's dense block (the hybrid ROI's
  /// K~), in place of K_lin's assembled entries; K_lin stays for the tangent.
  void use_split_products(SplitMatrix K_split, const SparseMatrix& K_elements) {
    K_split.sparse = SparseMatrix(K_split.sparse - K_elements);  // K_lin's sparse part; the dense block unchanged
    K_split_ = std::make_shared<const SplitMatrix>(std::move(K_split));
  }
  void force(double t, const Vector& u, Vector& f) const override;
  void force_and_tangent(double t, const Vector& u, Vector& f, SparseMatrix& K_t) const override;
  /// The law's elements' excess (fem::HyperelasticAssembler::excess_force): K = K_lin + their
  /// linear stiffness is the system's K, so this is f_int - K u.
  void excess_force(const Vector& u, Vector& g) const override;
  /// The elements' discrete gradient plus K_lin (u_a + u_b)/2 (exact for the quadratic K_lin part).
  void discrete_gradient(const Vector& u_a, const Vector& u_b, Vector& f_alg) const override;
  /// K_alg = K_lin / 2 + the elements' df_alg/du_b.
  void discrete_gradient_and_tangent(const Vector& u_a, const Vector& u_b, Vector& f_alg, SparseMatrix& K_alg) const override;
  double energy(double t, const Vector& u) const override;
  bool has_motion() const override { return motion_ != nullptr; }
  bool has_discrete_gradient() const override { return assembler_->has_discrete_gradient(); }
  Vector tool_force_correction(double t, const Vector& u) const override;
  std::shared_ptr<const InternalForce> with_ramp(const Ramp& ramp) const override;
  std::string describe() const override { return description_; }
  /// The elements that follow the law.
  const std::vector<Index>& elements() const { return assembler_->elements(); }

 private:
  /// The tools' part: their paths, the coupling matrices, and an assembler of the law's elements
  /// at the tools' nodes (their dofs its only free ones).
  struct Motion {
    std::vector<Tool> tools;
    SparseMatrix K_ug;  ///< n x 3T
    DenseMatrix K_gg;   ///< 3T x 3T
    std::shared_ptr<const fem::DofMap> tool_dofs;
    std::shared_ptr<const fem::HyperelasticAssembler> at_tools;
    std::vector<Index> component;  ///< tool_dofs' free dof i is tool component component[i] (3 a + c)
    Vector positions(double t) const;
  };
  static std::shared_ptr<const Motion> make_motion(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                   const fem::MaterialMap& materials, fem::Element element,
                                                   const std::vector<Index>& elements, std::vector<Tool> tools);
  /// The full displacement the elements read: u, the prescribed values, the tools' positions g.
  /// The full displacement the elements read (valid until the next call).
  const Vector& displacement(const Vector& u, const Vector& g) const;
  mutable Vector U_;  ///< displacement()'s
  Vector positions(double t) const { return motion_ ? motion_->positions(t) : Vector(); }

  std::shared_ptr<const fem::DofMap> dofs_;                      // before the assembler, which keeps a reference to it
  std::shared_ptr<const fem::HyperelasticAssembler> assembler_;  // shared by the copies with_ramp makes
  std::shared_ptr<const Motion> motion_;                         // null: no tool moves the law's elements
  /// K = share_of_K_lin K_lin + element_tangent_, in K_lin's pattern.
  void add_elements_to_K_lin(double share_of_K_lin, SparseMatrix& K) const;
  /// f += K_lin u.
  void add_linear(const Vector& u, Vector& f) const;
  SparseMatrix K_lin_;
  /// The hybrid's products: K_lin split, its sparse part K~'s less the law's elements' linear
  /// stiffness, its dense block the interface's (shared by the copies with_ramp makes).
  std::shared_ptr<const SplitMatrix> K_split_;
  mutable Vector linear_u_;
  bool K_lin_is_zero_;
  std::vector<int> assembler_in_K_;       ///< where the assembler's pattern's values land in K_lin's
  mutable SparseMatrix element_tangent_;  ///< the elements' tangent, in the assembler's pattern
  std::string description_;
};

/// The internal force of a full model when some material is hyperelastic (else null): those
/// tetrahedra by their law, the others by their linear K. `tools`: those whose nodes `dofs` holds,
/// on their paths. The nodal-pressure element takes a model whose every material is hyperelastic
/// (its nodal averages would mix the laws with linear elements): InputError naming the linear one
/// otherwise.
std::shared_ptr<const InternalForce> hyperelastic_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                        const fem::MaterialMap& materials, fem::Element element,
                                                        const std::vector<Tool>& tools = {});

/// The hybrid ROI's internal force over the ROI dofs of a static condensation (partition.d, in
/// order), from the condensed K~ (the reduced system's K, and its split form K_split for products,
/// where it has one) and the full model's dofs and materials.
std::shared_ptr<const InternalForce> hybrid_roi_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                      const fem::MaterialMap& materials, fem::Element element,
                                                      const roi::Partition& partition, const SparseMatrix& K_condensed,
                                                      const std::vector<Tool>& tools = {}, const SplitMatrix* K_split = nullptr);

/// The hybrid ROI's law on the full model, uncondensed: the elements the hybrid takes nonlinear
/// (neo-Hookean, no node in `partition`'s static part) by the law, every other by the full model's
/// K. Against the full neo-Hookean model it measures the linear remainder's error alone, and the
/// hybrid against it the condensation's (experiments/roi_size.hpp).
std::shared_ptr<const InternalForce> hybrid_law_uncondensed(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                            const fem::MaterialMap& materials, fem::Element element,
                                                            const roi::Partition& partition, const SparseMatrix& K,
                                                            const std::vector<Tool>& tools = {});

}  // namespace roifem::model
