// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where each stored value of a sparse matrix A lands among the stored values of a matrix J whose
/// pattern contains A's (both compressed, column-major, sorted rows): J.valuePtr()[at[k]] is the
/// entry of A.valuePtr()[k]. With it, J's values are summed from A's without a sparse sum's
/// allocation (the Newton Jacobian, the hybrid ROI's tangent).
#include <algorithm>
#include <vector>

#include "common/errors.hpp"
#include "common/types.hpp"

namespace roifem::solvers {

inline std::vector<int> positions_in(const SparseMatrix& A, const SparseMatrix& J) {
  if (A.rows() != J.rows() || A.cols() != J.cols() || !A.isCompressed() || !J.isCompressed())
    throw Error("internal: positions_in: the matrices differ in size or are not compressed");
  std::vector<int> at;
  at.reserve(static_cast<std::size_t>(A.nonZeros()));
  for (Index j = 0; j < A.outerSize(); ++j) {
    const int* begin = J.innerIndexPtr() + J.outerIndexPtr()[j];
    const int* end = J.innerIndexPtr() + J.outerIndexPtr()[j + 1];
    for (int k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k) {
      const int* found = std::lower_bound(begin, end, A.innerIndexPtr()[k]);
      if (found == end || *found != A.innerIndexPtr()[k]) throw Error("internal: positions_in: A's pattern is not within J's");
      at.push_back(static_cast<int>(found - J.innerIndexPtr()));
    }
  }
  return at;
}

/// s A + B in the union of A's and B's patterns, value by value: a Newton matrix from a tangent and
/// an inertia (the trapezoid's, energy-momentum's) without a sparse sum's allocation per iteration.
class PatternSum {
 public:
  PatternSum() = default;
  /// The patterns of A and B (compressed), which every later call's A and B keep.
  PatternSum(const SparseMatrix& A, const SparseMatrix& B) : pattern_(A + B) {
    pattern_.makeCompressed();
    A_in_ = positions_in(A, pattern_);
    B_in_ = positions_in(B, pattern_);
  }
  /// out = s A + B; out takes the union's pattern on the first call, later ones write values only.
  void assign(double s, const SparseMatrix& A, const SparseMatrix& B, SparseMatrix& out) const {
    if (out.nonZeros() != pattern_.nonZeros() || out.rows() != pattern_.rows()) out = pattern_;
    double* values = out.valuePtr();
    std::fill(values, values + out.nonZeros(), 0.0);
    const double* a = A.valuePtr();
    for (std::size_t i = 0; i < A_in_.size(); ++i) values[A_in_[i]] += s * a[i];
    const double* b = B.valuePtr();
    for (std::size_t i = 0; i < B_in_.size(); ++i) values[B_in_[i]] += b[i];
  }

 private:
  SparseMatrix pattern_;
  std::vector<int> A_in_, B_in_;
};

}  // namespace roifem::solvers
