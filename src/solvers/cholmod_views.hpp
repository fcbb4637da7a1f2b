// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// CHOLMOD headers over Eigen's arrays (no copy), and its status turned into an exception:
/// internal to the solvers.
#include <cholmod.h>

#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/types.hpp"

namespace roifem::solvers::detail {

/// A symmetric matrix stored in full or lower form; CHOLMOD reads its lower triangle.
inline cholmod_sparse symmetric_view(const SparseMatrix& A) {
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(A.rows());
  s.ncol = static_cast<std::size_t>(A.cols());
  s.nzmax = static_cast<std::size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = -1;  // symmetric, lower triangle used
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

/// The same symmetric matrix for CHOLMOD's 64-bit interface (cholmod_l_*): the index arrays copied
/// to SuiteSparse_long, the values still Eigen's. For factors beyond 2^31 entries (the 300k-node
/// brain's static part).
struct LongSymmetricView {
  std::vector<SuiteSparse_long> p, i;
  cholmod_sparse view{};

  explicit LongSymmetricView(const SparseMatrix& A)
      : p(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1), i(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros()) {
    view = symmetric_view(A);
    view.p = p.data();
    view.i = i.data();
    view.itype = CHOLMOD_LONG;
  }
  LongSymmetricView(const LongSymmetricView&) = delete;
  LongSymmetricView& operator=(const LongSymmetricView&) = delete;
};

/// A column-major dense block of rows x cols.
inline cholmod_dense dense_view(const double* data, Index rows, Index cols) {
  cholmod_dense d{};
  d.nrow = static_cast<std::size_t>(rows);
  d.ncol = static_cast<std::size_t>(cols);
  d.nzmax = d.nrow * d.ncol;
  d.d = d.nrow;
  d.x = const_cast<double*>(data);
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

/// Throws SolverError when a CHOLMOD call failed (`ok` false or an error status), naming `what`.
inline void check_status(const cholmod_common& common, bool ok, const char* what) {
  if (ok && common.status >= CHOLMOD_OK) return;
  const char* why = common.status == CHOLMOD_OUT_OF_MEMORY ? ": out of memory"
                    : common.status == CHOLMOD_TOO_LARGE
                        ? ": the factor would need more than 2^31 entries, beyond CHOLMOD's 32-bit interface"
                        : "";
  throw SolverError(std::string("CHOLMOD ") + what + " failed (status " + std::to_string(common.status) + why + ")");
}

}  // namespace roifem::solvers::detail
