// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What both IDA integrators (the residual form and the ROI DAE) share.
#include "integrators/integrator.hpp"
#include "integrators/sundials/handles.hpp"

namespace roifem::integrators::sundials {

/// J = dF/dy + c_j dF/dy' for two matrices built on one pattern (assemble_blocks' pattern_of).
void write_newton_matrix(const SparseMatrix& dF_dy, const SparseMatrix& dF_dyp, double c_j, SUNMatrix J);

/// IDA's counters (zero before IDAInit).
Stats ida_stats(void* ida_memory);

}  // namespace roifem::integrators::sundials
