#pragma once
/// The semi-discrete equations of motion every integrator solves:
///   M u'' + C u' + K u = f(t)
/// M symmetric positive definite (lumped: diagonal), C = alpha M, K symmetric positive definite.
/// The full model and a condensed ROI model are both of this form.
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

struct SecondOrderSystem {
  SparseMatrix M, C, K;      ///< in full, for factorizations
  LoadHistory load;
  SplitMatrix K_split;       ///< optional: the same K, split, for products
  SplitMatrix M_split;       ///< optional: the same M, split (Guyan, Craig-Bampton)
  /// The last dofs are this many modal coordinates q (Craig-Bampton, POD): M_qq = I exactly,
  /// K_qq diagonal, K_dq = 0, and M couples q to the rest only through M_split's block. An
  /// integrator may eliminate them in closed form (integrators/modal_elimination.hpp).
  Index modal_coordinates = 0;
  Index size() const { return K.rows(); }
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
};

/// alpha when C = alpha M (mass-proportional damping, to `tolerance` relative), else NaN.
double mass_proportional_damping(const SecondOrderSystem& system, double tolerance = 1e-12);

/// A diagonal as a sparse matrix.
SparseMatrix diagonal_matrix(const Vector& d);

/// Energies of a state: kinetic v^T M v / 2 and strain u^T K u / 2 (J), through the split M and K
/// where the system has them.
double kinetic_energy(const SecondOrderSystem& sys, const State& s);
double strain_energy(const SecondOrderSystem& sys, const State& s);

}  // namespace roifem::model
