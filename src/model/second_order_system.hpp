#pragma once
/// The semi-discrete equations of motion every integrator solves:
///   M u'' + C u' + K u = f(t)
/// M symmetric positive definite (lumped: diagonal), C = alpha M, K symmetric positive definite.
/// The full model and a condensed ROI model are both of this form.
#include "common/types.hpp"
#include "model/load_history.hpp"

namespace roifem::model {

/// K as a sparse part plus a dense block on a subset of dofs, K = K_sparse + P^T B P: how a
/// condensed stiffness is kept (K_dd and the interface Schur block) so that products run the
/// dense block through BLAS instead of as 76k scattered sparse entries.
struct SplitStiffness {
  SparseMatrix sparse;
  std::vector<Index> index;  ///< the block's dofs (P)
  DenseMatrix block;         ///< B, symmetric (products read its lower triangle)
  bool empty() const { return index.empty(); }
};

struct SecondOrderSystem {
  SparseMatrix M, C, K;      ///< K in full, for factorizations
  LoadHistory load;
  SplitStiffness K_split;    ///< optional: the same K, split, for products
  Index size() const { return K.rows(); }
  /// y = K x, through K_split when there is one.
  void apply_stiffness(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const;
};

/// Displacement and velocity at time t.
struct State {
  double t = 0;
  Vector u, v;
};

/// A diagonal as a sparse matrix.
SparseMatrix diagonal_matrix(const Vector& d);

/// Energies of a state: kinetic v^T M v / 2 and strain u^T K u / 2 (J).
double kinetic_energy(const SecondOrderSystem& sys, const State& s);
double strain_energy(const SecondOrderSystem& sys, const State& s);

}  // namespace roifem::model
