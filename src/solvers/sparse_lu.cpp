// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/sparse_lu.hpp"

#include <klu.h>

#include <string>

#include "common/errors.hpp"

namespace roifem::solvers {

struct SparseLu::Impl {
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  Index n = 0;

  Impl() {
    klu_defaults(&common);
    common.tol = 1.0;
  }
  ~Impl() {
    free_numeric();
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  void free_numeric() {
    if (numeric) klu_free_numeric(&numeric, &common);
  }
};

SparseLu::SparseLu() : impl_(std::make_unique<Impl>()) {}
SparseLu::SparseLu(SparseLu&&) noexcept = default;
SparseLu& SparseLu::operator=(SparseLu&&) noexcept = default;
SparseLu::~SparseLu() = default;

namespace {

void check_square_and_compressed(const SparseMatrix& A) {
  if (A.rows() != A.cols() || !A.isCompressed())
    throw Error("internal: SparseLu takes a square, compressed matrix, not " + std::to_string(A.rows()) + " x " +
                std::to_string(A.cols()) + (A.isCompressed() ? "" : " (uncompressed)"));
}

}  // namespace

void SparseLu::analyze(const SparseMatrix& A) {
  check_square_and_compressed(A);
  impl_->free_numeric();
  if (impl_->symbolic) klu_free_symbolic(&impl_->symbolic, &impl_->common);
  const int n = static_cast<int>(A.rows());
  // KLU's prototypes take non-const pointers; it does not write through them.
  impl_->symbolic = klu_analyze(n, const_cast<int*>(A.outerIndexPtr()), const_cast<int*>(A.innerIndexPtr()), &impl_->common);
  if (!impl_->symbolic) throw SolverError("KLU: the analysis failed (status " + std::to_string(impl_->common.status) + ")");
  impl_->n = A.rows();
}

void SparseLu::factorize(const SparseMatrix& A) {
  check_square_and_compressed(A);
  if (!impl_->symbolic || impl_->n != A.rows()) analyze(A);
  impl_->free_numeric();
  impl_->numeric = klu_factor(const_cast<int*>(A.outerIndexPtr()), const_cast<int*>(A.innerIndexPtr()),
                              const_cast<double*>(A.valuePtr()), impl_->symbolic, &impl_->common);
  if (!impl_->numeric || impl_->common.status == KLU_SINGULAR)
    throw SolverError("the matrix is singular to working precision (KLU: zero pivot in column " +
                      std::to_string(impl_->common.singular_col) + ")");
}

void SparseLu::solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) {
  if (!impl_->numeric || b.size() != impl_->n || x.size() != impl_->n) throw Error("internal: SparseLu::solve before factorize");
  x = b;
  if (!klu_solve(impl_->symbolic, impl_->numeric, static_cast<int>(impl_->n), 1, x.data(), &impl_->common))
    throw SolverError("KLU: the solve failed (status " + std::to_string(impl_->common.status) + ")");
}

Index SparseLu::size() const { return impl_->n; }

double SparseLu::rcond() {
  if (!impl_->numeric) return 0;
  klu_rcond(impl_->symbolic, impl_->numeric, &impl_->common);
  return impl_->common.rcond;
}

}  // namespace roifem::solvers
