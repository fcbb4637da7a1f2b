// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The BLAS's thread count for one scope, restored when the scope ends.
///
/// CHOLMOD's supernodal solve makes a few BLAS calls (dtrsv, dgemv) per supernode. For a small
/// factor they are small, and a threaded OpenBLAS spends more handing each one to its threads than
/// it saves (see cholesky.cpp). Large factorizations and solves still want every thread.
///
/// OpenBLAS only: its `openblas_set_num_threads` is looked up by name at run time, so that roifem
/// links against any BLAS; with another BLAS the scope does nothing. The count is one per process:
/// scopes suit a program that calls the BLAS from one thread, as roifem does.
namespace roifem::solvers {

class BlasThreadsScope {
 public:
  static constexpr int unchanged = 0;
  /// threads >= 1: the count for this scope; `unchanged`: leave it as it is.
  explicit BlasThreadsScope(int threads);
  BlasThreadsScope(const BlasThreadsScope&) = delete;
  BlasThreadsScope& operator=(const BlasThreadsScope&) = delete;
  ~BlasThreadsScope();

  /// Whether the BLAS lets its thread count be set (OpenBLAS).
  static bool controllable();
  /// The BLAS's thread count now (1 where it is not controllable).
  static int current();

 private:
  int previous_ = 0;  ///< 0: nothing to restore
};

}  // namespace roifem::solvers
