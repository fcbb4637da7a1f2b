// SPDX-License-Identifier: GPL-3.0-or-later
// The BLAS products against Eigen's own, with and without an accumulated y, and the BLAS's thread
// count left as it was.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/dense_blas.hpp"

namespace roifem::solvers {
namespace {

TEST(DenseBlas, ProductsEqualEigensAndAccumulate) {
  const DenseMatrix A = DenseMatrix::Random(37, 23);
  DenseMatrix S = DenseMatrix::Random(37, 37);
  S = (S + S.transpose()).eval();
  DenseMatrix S_lower = S.triangularView<Eigen::Lower>();  // the upper triangle must not be read
  S_lower.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  const Vector x = Vector::Random(23), z = Vector::Random(37), y0 = Vector::Random(37), q0 = Vector::Random(23);
  const int threads = BlasThreadsScope::current();

  Vector y = y0;
  multiply(A, x, 0.5, y);
  EXPECT_LT((y - (A * x + 0.5 * y0)).norm(), 1e-14 * y.norm());
  Vector q = q0;
  multiply_transposed(A, z, 1.0, q);
  EXPECT_LT((q - (A.transpose() * z + q0)).norm(), 1e-14 * q.norm());
  y = y0;
  multiply_symmetric(S_lower, z, 0.0, y);
  EXPECT_LT((y - S * z).norm(), 1e-14 * y.norm());

  EXPECT_EQ(BlasThreadsScope::current(), threads);
  Vector wrong(5);
  EXPECT_THROW(multiply(A, wrong, 0.0, y), Error);
  EXPECT_THROW(multiply_symmetric(S, z, 0.0, q), Error);
}

TEST(DenseBlas, AnEmptyBlockScalesY) {
  const DenseMatrix empty(4, 0);
  Vector y = Vector::Ones(4);
  multiply(empty, Vector(0), 2.0, y);
  EXPECT_EQ(y, Vector::Constant(4, 2.0));
}

}  // namespace
}  // namespace roifem::solvers
