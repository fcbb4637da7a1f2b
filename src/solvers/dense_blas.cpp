// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/dense_blas.hpp"

#include <limits>

#include "common/errors.hpp"
#include "solvers/blas_threads.hpp"

// The reference BLAS's Fortran interface, which every BLAS (OpenBLAS, reference, MKL) exports.
extern "C" {
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a, const int* lda, const double* x,
            const int* incx, const double* beta, double* y, const int* incy);
void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda, const double* x,
            const int* incx, const double* beta, double* y, const int* incy);
}

namespace roifem::solvers {

namespace {

int blas_int(Index n) {
  if (n > std::numeric_limits<int>::max()) throw Error("internal: a dense block too large for the BLAS's int");
  return static_cast<int>(n);
}

void gemv(char trans, const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y) {
  const bool t = trans == 'T';
  if (x.size() != (t ? A.rows() : A.cols()) || y.size() != (t ? A.cols() : A.rows()))
    throw Error("internal: dense product: size mismatch");
  if (A.size() == 0) {
    y *= beta;
    return;
  }
  const BlasThreadsScope one_thread(1);
  const int m = blas_int(A.rows()), n = blas_int(A.cols()), one = 1;
  const double alpha = 1.0;
  dgemv_(&trans, &m, &n, &alpha, A.data(), &m, x.data(), &one, &beta, y.data(), &one);
}

}  // namespace

void multiply(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y) {
  gemv('N', A, x, beta, y);
}

void multiply_transposed(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y) {
  gemv('T', A, x, beta, y);
}

void multiply_symmetric(const DenseMatrix& A, const Eigen::Ref<const Vector>& x, double beta, Eigen::Ref<Vector> y) {
  if (A.rows() != A.cols() || x.size() != A.rows() || y.size() != A.rows())
    throw Error("internal: symmetric dense product: size mismatch");
  if (A.size() == 0) return;  // y is empty too
  const BlasThreadsScope one_thread(1);
  const int n = blas_int(A.rows()), one = 1;
  const double alpha = 1.0;
  const char lower = 'L';
  dsymv_(&lower, &n, &alpha, A.data(), &n, x.data(), &one, &beta, y.data(), &one);
}

}  // namespace roifem::solvers
