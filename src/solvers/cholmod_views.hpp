#pragma once
/// CHOLMOD headers over Eigen's arrays (no copy): internal to the solvers.
#include <cholmod.h>

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

}  // namespace roifem::solvers::detail
