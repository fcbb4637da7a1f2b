// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Vectorized kernels for NVECTOR_SERIAL. Debian's SUNDIALS 6.4 builds its serial vector loops
/// without SIMD (one dependent add at a time: docs/design-figures.md), and ARKODE takes a weighted
/// RMS norm every step. N_Vector operations are a table of
/// function pointers meant to be replaced, and clones inherit it, so the integrators hand SUNDIALS
/// vectors whose hot operations run through Eigen instead (same results to rounding; a test checks
/// each against the library's own).
#include <sundials/sundials_nvector.h>

namespace roifem::integrators::sundials {

/// Replaces the element-wise operations, norms and fused linear combinations of a serial vector
/// (and of every vector later cloned from it) with vectorized versions.
void use_vectorized_ops(N_Vector v);

}  // namespace roifem::integrators::sundials
