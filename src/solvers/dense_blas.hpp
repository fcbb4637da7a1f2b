// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Dense matrix-vector products through the BLAS, on one thread.
///
/// Why not Eigen's: roifem is compiled for baseline x86-64, so Eigen's products run on SSE2, while
/// OpenBLAS picks its kernels for the CPU at run time (AVX2 and FMA), which at the reduced models'
/// sizes run the products in about half the time (docs/design-figures.md). One thread: at these
/// sizes a threaded OpenBLAS spends more handing the work out than it saves.
#include "common/types.hpp"

namespace roifem::solvers {

/// y = A x + beta y.
void multiply(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y);
/// y = A^T x + beta y.
void multiply_transposed(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y);
/// y = A x + beta y for a symmetric A, of which the lower triangle is read.
void multiply_symmetric(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y);

}  // namespace roifem::solvers
