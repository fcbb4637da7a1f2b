// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// An ROI model with its static part reduced: static condensation (Bro-Nielsen; Hansen & Larsen 1998),
///   K~ = K_dd - K_ds K_ss^-1 K_sd,   f~(t) = f_d(t) - K_ds K_ss^-1 f_s(t),
///   u_s = K_ss^-1 (f_s - K_sd u_d)    (the static part follows the ROI instantly).
/// One Cholesky factorization of K over the static dofs and the interface I, with I ordered last
/// (StaticPartFactor), gives both S = K_Is K_ss^-1 K_sI (dense, #I x #I) from the factor's
/// trailing block, and solves with K_ss from its leading block: no solve per interface column and
/// no dense #s x #I matrix X = K_ss^-1 K_sI (Guyan and Craig-Bampton form X, for their mass).
/// K~ = K_dd - S on the interface block, f~ pattern = f_d - K_Is K_ss^-1 f_s, and
/// u_s = z(t) - K_ss^-1 K_sI u_I with z(t) = sum_k r_k(t) K_ss^-1 p_k,s precomputed per load
/// pattern. The condensed system keeps K~ both assembled (for factorizations) and split as K_dd
/// plus the dense block -S (for products).
///
/// Four reductions share that machinery (T maps the reduced coordinates to all free dofs; the
/// kinds are described once in reduction.hpp's table). The construction runs in named steps: the
/// static part's factor (static_part_factor.hpp), the static modes X where mass is carried, the
/// basis of the kind (static_basis.hpp), and the reduction of K, M, C and f (reduced_operators.hpp):
///  - static condensation (the paper's): M and C of the ROI kept as they are; the static part
///    answers without inertia.
///  - Guyan: T = [I; -X P] (P picks the interface), M~ = T^T M T = M_dd + P^T X^T M_ss X P, and
///    C~ likewise: the static part's mass moves with the ROI through its static modes.
///  - Craig-Bampton: k fixed-interface modes Phi of (K_ss, M_ss) (M_ss-orthonormal, K_ss Phi =
///    M_ss Phi W^2) added as generalized coordinates eta: T = [[I, 0], [-X P, Phi]], so
///    K_r = diag(K~, W^2), M_r = [[M~, -P^T X^T M_ss Phi], [sym, I]], f_r = [f~; Phi^T f_s],
///    u_s = z(t) - Phi W^-2 Phi^T f_s(t) - X u_I + Phi eta. With every mode it is exact.
///  - POD: the same with Phi learnt from the full model's step responses (pod_basis.hpp): any
///    M_ss-orthonormal Phi with Phi^T K_ss Phi = W^2 diagonal fits the formulas above.
/// M and C of the full model must be diagonal (lumped) for Guyan and Craig-Bampton.
#include <memory>

#include "condensation/reduction.hpp"
#include "condensation/static_part_factor.hpp"
#include "fem/dof_map.hpp"
#include "model/second_order_system.hpp"
#include "model/spectrum.hpp"
#include "model/system_change.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

struct CondensationTimings {
  double factorization_s = 0;    ///< ordering and the factorization of K over s and I
  double interface_solve_s = 0;  ///< S read off the factor (and X, where mass is carried)
  double modes_s = 0, assembly_s = 0;
};

class ReducedModel {
 public:
  /// Throws ModelError when K_ss is singular (a static piece held by no fixed node), naming the node.
  /// InputError for a Craig-Bampton request without modes or a cut-off, or a non-diagonal M or C.
  ReducedModel(const model::SecondOrderSystem& full, const roi::Partition& partition, const fem::DofMap& dofs,
               const Reduction& reduction = {});

  /// The reduced system: the ROI dofs d first, then the basis coordinates eta.
  const model::SecondOrderSystem& system() const { return reduced_; }
  /// Gives the reduced system its DAE form with the tools' dofs kept (system().constrained).
  void attach_constrained_form(std::shared_ptr<const model::ConstrainedForm> form) { reduced_.constrained = std::move(form); }
  /// Gives the reduced system (a static condensation) the full system it came from
  /// (system().uncondensed).
  void attach_uncondensed_form(std::shared_ptr<const model::UncondensedForm> form) { reduced_.uncondensed = std::move(form); }
  /// Gives the reduced system a nonlinear internal force in place of K~ u (the hybrid ROI:
  /// model/hyperelastic_force.hpp); the condensation itself stays the linear model's.
  void attach_internal_force(std::shared_ptr<const model::InternalForce> force) { reduced_.internal_force = std::move(force); }
  /// Changes the reduced system in place on ROI dofs (a cut: model/system_change.hpp); the static
  /// part, its factor and the interface block stay as they are.
  void change_system(model::SystemChange& change) { change.apply(reduced_); }
  const roi::Partition& partition() const { return partition_; }
  const Reduction& reduction() const { return reduction_; }
  /// Static-part vectors kept (Craig-Bampton modes or POD vectors), and their (Ritz) frequencies (rad/s).
  Index num_modes() const { return basis_.omega.size(); }
  const Vector& mode_frequencies() const { return basis_.omega; }
  /// u over all free dofs from the reduced coordinates y = [u_d; eta] at time t (u_s recovered).
  /// Non-const: recovering u_s solves with the static part's factor, whose workspace it writes
  /// (one thread at a time per model).
  Vector expand(const Vector& y, double t);
  /// u_s alone.
  Vector recover_static(const Vector& y, double t);
  /// K_ds K_ss^-1 K_sd: the interface block subtracted from K_dd.
  const DenseMatrix& interface_schur() const { return factor_->interface_schur(); }
  const CondensationTimings& timings() const { return timings_; }

 private:
  void validate(const model::SecondOrderSystem& full) const;
  void assemble(const model::SecondOrderSystem& full, const DenseMatrix& X);

  roi::Partition partition_;
  Reduction reduction_;
  std::unique_ptr<StaticPartFactor> factor_;
  model::Modes basis_;  ///< Phi (#s x k, M_ss-orthonormal) and W
  model::SecondOrderSystem reduced_;
  model::LoadHistory static_response_;  ///< per load term: K_ss^-1 p_s, less its modal part
  CondensationTimings timings_;
};

}  // namespace roifem::condensation
