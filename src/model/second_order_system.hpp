// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The semi-discrete equations of motion every integrator solves:
///   M u'' + C u' + K u = f(t)
/// M symmetric positive definite (lumped: diagonal), C = alpha M, K symmetric positive definite.
/// The full model and a condensed ROI model are both of this form.
#include <memory>
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "model/load_history.hpp"

namespace roifem::model {

/// A symmetric matrix as a sparse part plus a dense block on a subset of dofs, A = A_sparse + P^T B P:
/// how a condensed stiffness (K_dd and the interface Schur block) and a Guyan or Craig-Bampton mass
/// are kept, so that products run the dense block as a symmetric BLAS-style product (reading half
/// of it) instead of as tens of thousands of scattered sparse entries.
struct SplitMatrix {
  SparseMatrix sparse;
  std::vector<Index> index;  ///< the block's dofs (P)
  DenseMatrix block;         ///< B, symmetric (products read its lower triangle)
  bool empty() const { return index.empty(); }
  /// y = A x.
  void apply(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const;
};

/// What C is: C = alpha M (Rayleigh mass-proportional damping: every FEM model here, and every
/// reduction of one, since T^T (alpha M) T = alpha T^T M T), or a general matrix.
struct Damping {
  enum class Kind { general, mass_proportional };
  Kind kind = Kind::general;
  double alpha = 0;  ///< 1/s, with mass_proportional
  static Damping mass_proportional(double alpha) { return {Kind::mass_proportional, alpha}; }
  bool is_mass_proportional() const { return kind == Kind::mass_proportional; }
};

/// Modal coordinates declared by a reduction (Craig-Bampton, POD): the last `count` dofs q, with
/// M_qq = I exactly, K_qq = diag(K) there, K_dq = 0, and M coupling q to the ROI dofs only
/// through M_split's dense block, whose index lists `interface_dofs` and then q in order. An
/// integrator may eliminate them in closed form (integrators/modal_elimination.hpp).
struct ModalBlock {
  Index count = 0;
  Index interface_dofs = 0;  ///< the first entries of M_split.index
};

struct ConstrainedForm;  // prescribed_motion.hpp
class InternalForce;     // internal_force.hpp
struct UncondensedForm;  // uncondensed_form.hpp

struct SecondOrderSystem {
  SparseMatrix M, C, K;  ///< in full, for factorizations
  LoadHistory load;
  SplitMatrix K_split;              ///< optional: the same K, split, for products
  SplitMatrix M_split;              ///< optional: the same M, split (Guyan, Craig-Bampton)
  Damping damping;                  ///< what C is (general unless declared)
  std::optional<ModalBlock> modal;  ///< set by reductions with modal coordinates
  /// Set where tools were eliminated from a larger system: that system and its tools, for the
  /// DAE formulations that keep the tools' dofs as unknowns (integrators/ida_tool_dae.hpp).
  std::shared_ptr<const ConstrainedForm> constrained;
  /// Set on a static condensation: the full system it came from, for the DAE that keeps the static
  /// part as algebraic unknowns (integrators/ida_roi_dae.hpp).
  std::shared_ptr<const UncondensedForm> uncondensed;
  /// Set on a nonlinear model: f_int(u) replaces K u in the equation, and K is its tangent at rest
  /// (internal_force.hpp). Only the methods whose table row says `nonlinear` take it.
  std::shared_ptr<const InternalForce> internal_force;
  Index size() const { return K.rows(); }
  bool is_nonlinear() const { return internal_force != nullptr; }
  /// y = K x, through K_split when there is one.
  void apply_stiffness(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const;
  /// y = M x, through M_split when there is one.
  void apply_mass(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const;
  /// The dofs of K_split's and M_split's dense blocks, ascending: what a factorization of
  /// K + c M orders last, so that they form one dense supernode.
  std::vector<Index> dense_block_dofs() const;
};

/// Displacement and velocity at time t.
struct State {
  double t = 0;
  Vector u, v;
  /// u = v = 0 at t over n dofs.
  static State at_rest(Index n, double t = 0) { return {t, Vector::Zero(n), Vector::Zero(n)}; }
};

/// alpha when C = alpha M (mass-proportional damping, to `tolerance` relative), else NaN.
double mass_proportional_damping(const SecondOrderSystem& system, double tolerance = 1e-12);

/// The same system with every load term, and a nonlinear law's tools' paths, on `ramp`
/// (LoadHistory::with_ramp, InternalForce::with_ramp).
SecondOrderSystem with_ramp(const SecondOrderSystem& system, const Ramp& ramp);

/// A diagonal as a sparse matrix.
SparseMatrix diagonal_matrix(const Vector& d);

/// Energies of a state: kinetic v^T M v / 2 and strain u^T K u / 2 (J), through the split M and K
/// where the system has them; a nonlinear system's strain energy is its W(u).
double kinetic_energy(const SecondOrderSystem& sys, const State& s);
double strain_energy(const SecondOrderSystem& sys, const State& s);

}  // namespace roifem::model
