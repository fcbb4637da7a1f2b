// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/cholesky.hpp"

#include <cstring>
#include <string>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/cholmod_views.hpp"
#include "solvers/serial_openmp.hpp"

namespace roifem::solvers {

using detail::dense_view;
using detail::symmetric_view;

namespace {
// A single-vector solve with a supernodal factor of fewer entries than this (40 MB) runs the BLAS
// on one thread (see blas_threads.hpp). OpenBLAS threads a dgemv above 9,216 entries, so a small
// factor's solve pays a hand-off per supernode for little work, while a large factor's solve
// gains from the second thread (the measured threshold: docs/design-figures.md).
constexpr double one_thread_solve_below = 5e6;
}  // namespace

NotPositiveDefinite::NotPositiveDefinite(Index col, double rc)
    : std::runtime_error(col >= 0
                             ? "matrix is not positive definite (factorization stopped at column " + std::to_string(col) + ")"
                             : "matrix is singular to working precision (reciprocal condition " + number_text(rc) + ")"),
      column(col),
      rcond(rc) {}

struct Cholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  // Workspaces of cholmod_solve2, kept between solves.
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;

  explicit Impl(Kind kind) {
    cholmod_start(&common);
    common.supernodal = kind == Kind::simplicial   ? CHOLMOD_SIMPLICIAL
                        : kind == Kind::supernodal ? CHOLMOD_SUPERNODAL
                                                   : CHOLMOD_AUTO;
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    free_workspace();
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  void free_workspace() {
    if (x) cholmod_free_dense(&x, &common);
    if (y) cholmod_free_dense(&y, &common);
    if (e) cholmod_free_dense(&e, &common);
  }
  void check(bool ok, const char* what) const { detail::check_status(common, ok, what); }
};

Cholesky::Cholesky(Kind kind) : impl_(std::make_unique<Impl>(kind)) {}
Cholesky::Cholesky(Cholesky&&) noexcept = default;
Cholesky& Cholesky::operator=(Cholesky&&) noexcept = default;
Cholesky::~Cholesky() = default;

void Cholesky::analyze(const SparseMatrix& A) { analyze(A, {}); }

void Cholesky::analyze(const SparseMatrix& A, const std::vector<Index>& last) {
  if (A.rows() != A.cols()) throw Error("internal: Cholesky of a non-square matrix");
  if (!A.isCompressed()) throw Error("internal: Cholesky needs a compressed matrix");
  const std::size_t n = static_cast<std::size_t>(A.rows());
  std::vector<int> member(last.empty() ? 0 : n, 0);  // CAMD's constraint sets: 1 = ordered last
  for (Index i : last) {
    if (i < 0 || static_cast<std::size_t>(i) >= n)
      throw Error("internal: Cholesky: index " + std::to_string(i) + " to order last is out of range");
    member[static_cast<std::size_t>(i)] = 1;
  }
  cholmod_sparse a = symmetric_view(A);
  auto& common = impl_->common;
  impl_->free_workspace();
  if (impl_->factor) cholmod_free_factor(&impl_->factor, &common);
  if (last.empty()) {
    impl_->factor = cholmod_analyze(&a, &common);  // CHOLMOD's choice among AMD and METIS
  } else {
    std::vector<int> perm(n);
    impl_->check(cholmod_camd(&a, nullptr, 0, member.data(), perm.data(), &common), "constrained ordering");
    const int methods = common.nmethods, ordering = common.method[0].ordering;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
    impl_->factor = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &common);
    common.nmethods = methods;
    common.method[0].ordering = ordering;
  }
  impl_->check(impl_->factor != nullptr, "analysis");
}

void Cholesky::factorize(const SparseMatrix& A) {
  if (!impl_->factor || static_cast<Index>(impl_->factor->n) != A.rows()) analyze(A);
  cholmod_sparse a = symmetric_view(A);
  // A small supernodal factor: CHOLMOD's OpenMP regions on one thread (serial_openmp.hpp).
  const bool small = impl_->factor->is_super && static_cast<double>(impl_->factor->xsize) < one_thread_solve_below;
  int ok = 0;
  {
    const SerialOpenMpScope serial(small);
    ok = cholmod_factorize(&a, impl_->factor, &impl_->common);
  }
  if (impl_->common.status == CHOLMOD_NOT_POSDEF) {
    // CHOLMOD's `minor` counts columns of the permuted matrix; name the column of A.
    const auto* perm = static_cast<const int*>(impl_->factor->Perm);
    const std::size_t minor = impl_->factor->minor;
    throw NotPositiveDefinite(minor < impl_->factor->n && perm ? perm[minor] : -1, 0.0);
  }
  impl_->check(ok, "factorization");
  // A simplicial LDL^T factor (CHOLMOD's choice for a small or sparse-enough matrix) stops only at
  // a zero pivot: an indefinite matrix factors with a negative D(j, j). Positive definite means
  // every pivot positive.
  if (!impl_->factor->is_super && !impl_->factor->is_ll) {
    const auto* p = static_cast<const int*>(impl_->factor->p);
    const auto* x = static_cast<const double*>(impl_->factor->x);
    const auto* perm = static_cast<const int*>(impl_->factor->Perm);
    for (std::size_t j = 0; j < impl_->factor->n; ++j)
      if (!(x[p[j]] > 0)) throw NotPositiveDefinite(perm ? perm[j] : static_cast<Index>(j), 0.0);
  }
  // A positive semidefinite matrix (rigid-body modes) may factor with round-off-sized pivots.
  if (const double rc = rcond(); !(rc > 1e-15)) throw NotPositiveDefinite(-1, rc);
}

Vector Cholesky::solve(const Eigen::Ref<const Vector>& b) {
  Vector x(b.size());
  solve(b, x);
  return x;
}

void Cholesky::solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) {
  if (!impl_->factor) throw Error("internal: Cholesky::solve before factorize");
  const bool small = impl_->factor->is_super && static_cast<double>(impl_->factor->xsize) < one_thread_solve_below;
  const BlasThreadsScope blas(small ? 1 : BlasThreadsScope::unchanged);
  cholmod_dense rhs = dense_view(b.data(), b.size(), 1);
  auto* common = &impl_->common;
  const int ok = cholmod_solve2(CHOLMOD_A, impl_->factor, &rhs, nullptr, &impl_->x, nullptr, &impl_->y, &impl_->e, common);
  impl_->check(ok, "solve");
  std::memcpy(x.data(), impl_->x->x, sizeof(double) * static_cast<std::size_t>(b.size()));
}

DenseMatrix Cholesky::solve_matrix(const Eigen::Ref<const DenseMatrix>& B) {
  if (!impl_->factor) throw Error("internal: Cholesky::solve before factorize");
  const DenseMatrix Bc = B;  // contiguous, column-major
  cholmod_dense rhs = dense_view(Bc.data(), Bc.rows(), Bc.cols());
  auto* common = &impl_->common;
  cholmod_dense* X = cholmod_solve(CHOLMOD_A, impl_->factor, &rhs, common);
  impl_->check(X != nullptr, "solve");
  DenseMatrix result = Eigen::Map<const DenseMatrix>(static_cast<double*>(X->x), Bc.rows(), Bc.cols());
  cholmod_free_dense(&X, common);
  return result;
}

Index Cholesky::size() const { return impl_->factor ? static_cast<Index>(impl_->factor->n) : 0; }

std::vector<Index> Cholesky::ordering() const {
  if (!impl_->factor) throw Error("internal: Cholesky::ordering before analyze");
  const auto* perm = static_cast<const int*>(impl_->factor->Perm);
  return std::vector<Index>(perm, perm + impl_->factor->n);
}

double Cholesky::factor_nonzeros() const { return impl_->common.lnz; }

double Cholesky::rcond() { return impl_->factor ? cholmod_rcond(impl_->factor, &impl_->common) : 0.0; }

}  // namespace roifem::solvers
