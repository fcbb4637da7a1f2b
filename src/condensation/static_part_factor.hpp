// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The one factorization every reduction of the static part starts from: K over the static dofs
/// s and the interface I, with I ordered last (solvers::PartialCholesky). From it:
///   S = K_Is K_ss^-1 K_sI           the interface Schur block (dense, #I x #I), read off the factor,
///   K_ss^-1 b                        solves with the static part (the factor's leading block),
///   X = K_ss^-1 K_sI                 the static modes (dense, #s x #I), formed only when asked.
#include <memory>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "roi/roi.hpp"
#include "solvers/partial_cholesky.hpp"

namespace roifem::condensation {

class StaticPartFactor {
 public:
  /// Throws ModelError when K_ss is singular (a static piece held by no fixed node), naming the node.
  StaticPartFactor(const SparseMatrix& K, const roi::Partition& partition, const fem::DofMap& dofs);

  bool has_static_part() const { return factor_ != nullptr; }
  /// S = K_Is K_ss^-1 K_sI, symmetric (zero without a static part).
  const DenseMatrix& interface_schur() const { return schur_; }
  const SparseMatrix& K_sI() const { return K_sI_; }
  /// K_ss^-1 b over the static dofs. Non-const: solves write the factor's workspace (one thread at
  /// a time, solvers/cholesky.hpp).
  Vector solve_static(const Eigen::Ref<const Vector>& b) { return factor_->solve_leading(b); }
  void solve_static(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) { factor_->solve_leading(b, x); }
  /// X = K_ss^-1 K_sI (#s x #I): one solve per interface column.
  DenseMatrix static_modes();
  double factorization_s() const { return factorization_s_; }
  double schur_s() const { return schur_s_; }

 private:
  std::unique_ptr<solvers::PartialCholesky> factor_;  ///< K over s and I, I last; null without s
  SparseMatrix K_sI_;
  DenseMatrix schur_;
  Index n_s_ = 0;
  double factorization_s_ = 0, schur_s_ = 0;
};

}  // namespace roifem::condensation
