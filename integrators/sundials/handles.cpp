// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/handles.hpp"

#include <arkode/arkode_arkstep.h>
#include <ida/ida.h>

#include <algorithm>

namespace roifem::integrators::sundials {

void ArkodeMemoryDeleter::operator()(void* memory) const { ARKStepFree(&memory); }
void IdaMemoryDeleter::operator()(void* memory) const { IDAFree(&memory); }

Matrix make_sparse(const SparseMatrix& A, SUNContext ctx) {
  SUNMatrix m = SUNSparseMatrix(static_cast<sunindextype>(A.rows()), static_cast<sunindextype>(A.cols()),
                                static_cast<sunindextype>(A.nonZeros()), CSC_MAT, ctx);
  if (!m) throw SolverError("SUNDIALS: cannot allocate a sparse matrix");
  copy_into(A, m);
  return Matrix(m);
}

void copy_into(const SparseMatrix& A, SUNMatrix target) {
  sunindextype* col = SUNSparseMatrix_IndexPointers(target);
  sunindextype* row = SUNSparseMatrix_IndexValues(target);
  for (Index j = 0; j <= A.cols(); ++j) col[j] = A.outerIndexPtr()[j];
  for (Index k = 0; k < A.nonZeros(); ++k) row[k] = A.innerIndexPtr()[k];
  std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), SUNSparseMatrix_Data(target));
}

}  // namespace roifem::integrators::sundials
