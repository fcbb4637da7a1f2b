// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/system_change.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace roifem::model {

namespace {

/// A += U B U^T for a compressed sparse A: in place where A's pattern holds every entry B has (a
/// removal's: O(r^2 log) instead of a pass over all of A, whose dense interface block makes a
/// condensed model's K large), else by a sum (the pattern grows where a split couples new dofs).
/// The same sums either way: each entry gains b once.
void add_block(SparseMatrix& A, const std::vector<Index>& dofs, const DenseMatrix& B) {
  std::vector<double*> at;
  at.reserve(dofs.size() * dofs.size());
  bool in_pattern = A.isCompressed();
  for (std::size_t j = 0; j < dofs.size() && in_pattern; ++j)
    for (std::size_t i = 0; i < dofs.size() && in_pattern; ++i) {
      if (B(static_cast<Index>(i), static_cast<Index>(j)) == 0) continue;
      const int begin = A.outerIndexPtr()[dofs[j]], end = A.outerIndexPtr()[dofs[j] + 1];
      const int* rows = A.innerIndexPtr();
      const int* found = std::lower_bound(rows + begin, rows + end, static_cast<int>(dofs[i]));
      in_pattern = found != rows + end && *found == dofs[i];
      if (in_pattern) at.push_back(A.valuePtr() + (found - rows));
    }
  if (in_pattern) {
    std::size_t k = 0;
    for (std::size_t j = 0; j < dofs.size(); ++j)
      for (std::size_t i = 0; i < dofs.size(); ++i)
        if (const double b = B(static_cast<Index>(i), static_cast<Index>(j)); b != 0) *at[k++] += b;
    return;
  }
  std::vector<Eigen::Triplet<double, Index>> entries;
  entries.reserve(dofs.size() * dofs.size());
  for (std::size_t j = 0; j < dofs.size(); ++j)
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (const double b = B(static_cast<Index>(i), static_cast<Index>(j)); b != 0) entries.emplace_back(dofs[i], dofs[j], b);
  SparseMatrix change(A.rows(), A.cols());
  change.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix sum = A + change;
  A.swap(sum);  // Eigen 3.4's sparse matrices have no move assignment
}

void add_diagonal(SparseMatrix& A, const std::vector<Index>& dofs, const Vector& d) {
  DenseMatrix B = DenseMatrix::Zero(d.size(), d.size());
  B.diagonal() = d;
  add_block(A, dofs, B);
}

/// Zeroes the rows and columns `held` of A (stored entries kept, so the pattern stays).
void zero_rows_and_columns(SparseMatrix& A, const std::vector<bool>& is_held, bool any) {
  if (!any) return;
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (is_held[static_cast<std::size_t>(it.row())] || is_held[static_cast<std::size_t>(it.col())]) it.valueRef() = 0;
}

}  // namespace

SystemChange SystemChange::from_removal(const fem::ElementRemoval& removal, const fem::DofMap& dofs,
                                        const std::vector<Index>& system_dof, std::size_t load_terms) {
  SystemChange change;
  change.stiffness = removal.change;
  change.mass = removal.mass_change;
  for (std::size_t a = 0; a < removal.dofs.size(); ++a) {
    const Index free = removal.dofs[a];
    const Index d = system_dof[static_cast<std::size_t>(free)];
    if (d < 0) throw Error("internal: a removal reaches a dof the system does not have");
    change.dofs.push_back(d);
    if (std::binary_search(removal.orphan_nodes.begin(), removal.orphan_nodes.end(), static_cast<int>(dofs.full_dof(free) / 3))) {
      change.held.push_back(d);
      change.mass[static_cast<Index>(a)] = 0;
    }
  }
  change.loads.assign(load_terms, Vector());
  return change;
}

DenseMatrix SystemChange::effective(double c) const {
  DenseMatrix out = stiffness;
  out.diagonal() += c * mass;
  return out;
}

void SystemChange::apply(SecondOrderSystem& system) {
  if (!system.damping.is_mass_proportional())
    throw InputError("a cut changes M, and C with it only where C = alpha M: this system's damping is general");
  if (loads.size() != system.load.terms().size())
    throw Error("internal: a system change has " + std::to_string(loads.size()) + " load changes for " +
                std::to_string(system.load.terms().size()) + " load terms");
  const auto r = static_cast<Index>(dofs.size());
  // At held dofs dK takes exactly what K holds there, so that K's rows become zero, not round-off.
  std::vector<bool> is_held(static_cast<std::size_t>(system.size()), false);
  for (const Index d : held) is_held[static_cast<std::size_t>(d)] = true;
  for (Index a = 0; a < r; ++a)
    for (Index b = 0; b < r; ++b)
      if (is_held[static_cast<std::size_t>(dofs[static_cast<std::size_t>(a)])] ||
          is_held[static_cast<std::size_t>(dofs[static_cast<std::size_t>(b)])])
        stiffness(a, b) = -system.K.coeff(dofs[static_cast<std::size_t>(a)], dofs[static_cast<std::size_t>(b)]);
  add_block(system.K, dofs, stiffness);
  zero_rows_and_columns(system.K, is_held, !held.empty());
  if (!system.K_split.empty()) {
    add_block(system.K_split.sparse, dofs, stiffness);
    zero_rows_and_columns(system.K_split.sparse, is_held, !held.empty());
  }
  add_diagonal(system.M, dofs, mass);
  if (!system.M_split.empty()) add_diagonal(system.M_split.sparse, dofs, mass);
  add_diagonal(system.C, dofs, system.damping.alpha * mass);
  LoadHistory changed(system.load.size());
  for (std::size_t k = 0; k < loads.size(); ++k) {
    const auto& term = system.load.terms()[k];
    Vector pattern = term.pattern;
    if (loads[k].size() == r)
      for (Index a = 0; a < r; ++a) pattern[dofs[static_cast<std::size_t>(a)]] += loads[k][a];
    for (const Index d : held) pattern[d] = 0;
    changed.add(std::move(pattern), term.ramp);
  }
  system.load = std::move(changed);
}

}  // namespace roifem::model
