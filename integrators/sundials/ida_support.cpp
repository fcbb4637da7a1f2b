// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/ida_support.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>

namespace roifem::integrators::sundials {

void write_newton_matrix(const SparseMatrix& dF_dy, const SparseMatrix& dF_dyp, double c_j, SUNMatrix J) {
  copy_into(dF_dy, J);  // pattern and dF/dy's values (SUNDIALS zeroed J, index arrays included)
  double* values = SUNSparseMatrix_Data(J);
  const double* dyp = dF_dyp.valuePtr();
  for (Index k = 0; k < dF_dyp.nonZeros(); ++k) values[k] += c_j * dyp[k];
}

Stats ida_stats(void* memory) {
  Stats s;
  if (!memory) return s;
  IDAGetNumSteps(memory, &s.steps);
  IDAGetNumResEvals(memory, &s.rhs_evals);
  IDAGetNumJacEvals(memory, &s.jac_evals);
  IDAGetNumLinSolvSetups(memory, &s.lin_setups);
  IDAGetNumNonlinSolvIters(memory, &s.lin_solves);
  IDAGetNumErrTestFails(memory, &s.failed_steps);
  return s;
}

}  // namespace roifem::integrators::sundials
