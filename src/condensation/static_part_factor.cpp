// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/static_part_factor.hpp"

#include <algorithm>
#include <string>

#include "common/errors.hpp"
#include "common/timer.hpp"

namespace roifem::condensation {

namespace {

std::vector<Index> interface_as_free_dofs(const roi::Partition& partition) {
  std::vector<Index> dofs;
  for (Index k : partition.interface) dofs.push_back(partition.d[static_cast<std::size_t>(k)]);
  return dofs;
}

}  // namespace

StaticPartFactor::StaticPartFactor(const SparseMatrix& K, const roi::Partition& partition, const fem::DofMap& dofs)
    : n_s_(static_cast<Index>(partition.s.size())) {
  const std::vector<Index> interface_dofs = interface_as_free_dofs(partition);
  const auto n_i = static_cast<Index>(interface_dofs.size());
  if (partition.s.empty()) {
    schur_ = DenseMatrix::Zero(n_i, n_i);
    K_sI_.resize(0, n_i);
    return;
  }
  Stopwatch clock;
  // One factorization of K over the static dofs and the interface, the interface ordered last:
  // its trailing block is K_II - S, and its leading block solves with K_ss (no solve per
  // interface column, no dense #s x #I matrix).
  std::vector<Index> static_and_interface = partition.s;
  static_and_interface.insert(static_and_interface.end(), interface_dofs.begin(), interface_dofs.end());
  std::sort(static_and_interface.begin(), static_and_interface.end());
  std::vector<Index> trailing;
  trailing.reserve(interface_dofs.size());
  for (Index dof : interface_dofs)
    trailing.push_back(std::lower_bound(static_and_interface.begin(), static_and_interface.end(), dof) -
                       static_and_interface.begin());
  try {
    factor_ = std::make_unique<solvers::PartialCholesky>(roi::submatrix(K, static_and_interface, static_and_interface), trailing);
  } catch (const solvers::NotPositiveDefinite& e) {
    std::string where = "a part of it is free to move as a rigid body";
    if (e.column >= 0) {
      const Index node = dofs.full_dof(static_and_interface[static_cast<std::size_t>(e.column)]) / 3;
      where = "the factorization stopped at node " + std::to_string(node);
    }
    throw ModelError("static part K_ss is singular: " + where +
                     "; every static piece needs a fixed node or a connection to the ROI");
  }
  factorization_s_ = clock.seconds();
  clock.restart();
  K_sI_ = roi::submatrix(K, partition.s, interface_dofs);
  // S = K_II - (K_II - S); symmetric in exact arithmetic, and made so in floating point, so that
  // products (which read one triangle) and factorizations (the other) see the same matrix.
  const DenseMatrix K_II(roi::submatrix(K, interface_dofs, interface_dofs));
  schur_ = K_II - factor_->trailing_schur_complement();
  schur_ = (0.5 * (schur_ + schur_.transpose())).eval();
  schur_s_ = clock.seconds();
}

DenseMatrix StaticPartFactor::static_modes() {
  DenseMatrix X(n_s_, K_sI_.cols());
  if (!factor_) return X;
  const DenseMatrix K_sI(K_sI_);
  for (Index j = 0; j < X.cols(); ++j) X.col(j) = factor_->solve_leading(K_sI.col(j));
  return X;
}

}  // namespace roifem::condensation
