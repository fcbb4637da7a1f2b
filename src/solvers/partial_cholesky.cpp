// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/partial_cholesky.hpp"

#include <cstring>
#include <string>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "solvers/cholmod_views.hpp"

namespace roifem::solvers {

// CHOLMOD's 64-bit interface throughout (cholmod_l_*, SuiteSparse_long indices): the static part
// of the 300k-node brain factors to more than 2^31 entries, beyond the 32-bit one.
using Long = SuiteSparse_long;

struct PartialCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  Index n = 0, n_leading = 0;
  std::vector<Index> leading;       ///< A's leading indices, ascending
  std::vector<Long> leading_order;  ///< factor position k < n_leading -> position in `leading`
  double analysis_s = 0, factorization_s = 0;
  // Workspaces of cholmod_solve2, kept between solves.
  cholmod_dense *x1 = nullptr, *x2 = nullptr, *y = nullptr, *e = nullptr;
  Vector rhs;

  Impl() {
    cholmod_l_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    for (cholmod_dense** d : {&x1, &x2, &y, &e})
      if (*d) cholmod_l_free_dense(d, &common);
    if (factor) cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void check(bool ok, const char* what) const { detail::check_status(common, ok, what); }
};

PartialCholesky::PartialCholesky(const SparseMatrix& A, const std::vector<Index>& trailing) : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  if (A.rows() != A.cols()) throw Error("internal: PartialCholesky of a non-square matrix");
  m.n = A.rows();
  if (!A.isCompressed()) throw Error("internal: PartialCholesky needs a compressed matrix");
  std::vector<Long> new_index(static_cast<std::size_t>(m.n), 0);
  for (Index t : trailing) {
    if (t < 0 || t >= m.n || new_index[static_cast<std::size_t>(t)] < 0)
      throw Error("internal: PartialCholesky: trailing index " + std::to_string(t) + " out of range or repeated");
    new_index[static_cast<std::size_t>(t)] = -1;
  }
  for (Index i = 0; i < m.n; ++i)
    if (new_index[static_cast<std::size_t>(i)] == 0) {
      new_index[static_cast<std::size_t>(i)] = static_cast<Long>(m.leading.size());
      m.leading.push_back(i);
    } else {
      new_index[static_cast<std::size_t>(i)] = -1;
    }
  m.n_leading = static_cast<Index>(m.leading.size());

  Stopwatch clock;
  // 1. CHOLMOD's fill-reducing ordering of all of A (its usual choice among AMD and METIS), the
  //    trailing indices then moved to the end, the others keeping their relative order. One
  //    ordering instead of one for A_ll and one for A: the same fill, one METIS run fewer
  //    (docs/design-figures.md).
  detail::LongSymmetricView a(A);
  std::vector<Long> perm;
  perm.reserve(static_cast<std::size_t>(m.n));
  {
    cholmod_factor* symbolic = cholmod_l_analyze(&a.view, &m.common);
    m.check(symbolic != nullptr, "analysis");
    const auto* p = static_cast<const Long*>(symbolic->Perm);
    for (Index k = 0; k < m.n; ++k)
      if (const Long i = p[k]; new_index[static_cast<std::size_t>(i)] >= 0) {
        perm.push_back(i);
        m.leading_order.push_back(new_index[static_cast<std::size_t>(i)]);
      }
    cholmod_l_free_factor(&symbolic, &m.common);
  }
  for (Index t : trailing) perm.push_back(static_cast<Long>(t));

  // 2. That order with the trailing indices last, taken as given (no postordering, which could
  //    move trailing columns forward), supernodal so that the trailing block is read off dense.
  m.common.nmethods = 1;
  m.common.method[0].ordering = CHOLMOD_GIVEN;
  m.common.postorder = 0;
  m.common.supernodal = CHOLMOD_SUPERNODAL;
  m.factor = cholmod_l_analyze_p(&a.view, perm.data(), nullptr, 0, &m.common);
  m.check(m.factor != nullptr, "analysis");
  if (std::memcmp(m.factor->Perm, perm.data(), perm.size() * sizeof(Long)) != 0)
    throw Error("internal: PartialCholesky: CHOLMOD changed the given ordering");
  m.analysis_s = clock.seconds();
  clock.restart();
  const int ok = cholmod_l_factorize(&a.view, m.factor, &m.common);
  if (m.common.status == CHOLMOD_NOT_POSDEF) {
    const std::size_t minor = m.factor->minor;
    throw NotPositiveDefinite(minor < perm.size() ? static_cast<Index>(perm[minor]) : -1, 0.0);
  }
  m.check(ok, "factorization");
  if (!m.factor->is_super || !m.factor->is_ll) throw Error("internal: PartialCholesky: expected a supernodal LL^T factor");
  if (const double rc = cholmod_l_rcond(m.factor, &m.common); !(rc > 1e-15)) throw NotPositiveDefinite(-1, rc);
  m.factorization_s = clock.seconds();
}

PartialCholesky::PartialCholesky(PartialCholesky&&) noexcept = default;
PartialCholesky& PartialCholesky::operator=(PartialCholesky&&) noexcept = default;
PartialCholesky::~PartialCholesky() = default;

DenseMatrix PartialCholesky::trailing_schur_complement() const {
  const auto& m = *impl_;
  const cholmod_factor& L = *m.factor;
  const Index n_t = m.n - m.n_leading, first = m.n_leading;
  DenseMatrix L_tt = DenseMatrix::Zero(n_t, n_t);
  const auto* super = static_cast<const Long*>(L.super);
  const auto* pi = static_cast<const Long*>(L.pi);
  const auto* px = static_cast<const Long*>(L.px);
  const auto* rows = static_cast<const Long*>(L.s);
  const auto* x = static_cast<const double*>(L.x);
  // Supernode s holds columns super[s] .. super[s+1]-1 as a dense column-major block whose rows
  // are rows[pi[s] .. pi[s+1]), the first of them its own columns (its diagonal block).
  for (std::size_t s = 0; s < L.nsuper; ++s) {
    const Long k1 = super[s], k2 = super[s + 1];
    if (k2 <= first) continue;
    const Long nrows = pi[s + 1] - pi[s];
    for (Long j = std::max<Long>(k1, first); j < k2; ++j)
      for (Long p = j - k1; p < nrows; ++p)
        L_tt(static_cast<Index>(rows[pi[s] + p] - first), static_cast<Index>(j - first)) = x[px[s] + (j - k1) * nrows + p];
  }
  DenseMatrix S = DenseMatrix::Zero(n_t, n_t);
  S.selfadjointView<Eigen::Lower>().rankUpdate(L_tt);
  return S.selfadjointView<Eigen::Lower>();
}

void PartialCholesky::solve_leading(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) {
  auto& m = *impl_;
  if (b.size() != m.n_leading || x.size() != m.n_leading) throw Error("internal: PartialCholesky::solve_leading: size mismatch");
  // [b; 0] in factor order, L z = it, z's trailing part dropped, L^T w = [z_l; 0]: w_l = A_ll^-1 b.
  m.rhs.setZero(m.n);
  for (Index k = 0; k < m.n_leading; ++k) m.rhs[k] = b[m.leading_order[static_cast<std::size_t>(k)]];
  auto* common = &m.common;
  cholmod_dense rhs = detail::dense_view(m.rhs.data(), m.n, 1);
  m.check(cholmod_l_solve2(CHOLMOD_L, m.factor, &rhs, nullptr, &m.x1, nullptr, &m.y, &m.e, common), "solve");
  auto* z = static_cast<double*>(m.x1->x);
  std::fill(z + m.n_leading, z + m.n, 0.0);
  m.check(cholmod_l_solve2(CHOLMOD_Lt, m.factor, m.x1, nullptr, &m.x2, nullptr, &m.y, &m.e, common), "solve");
  const auto* w = static_cast<const double*>(m.x2->x);
  for (Index k = 0; k < m.n_leading; ++k) x[m.leading_order[static_cast<std::size_t>(k)]] = w[k];
}

Vector PartialCholesky::solve_leading(const Eigen::Ref<const Vector>& b) {
  Vector x(b.size());
  solve_leading(b, x);
  return x;
}

const std::vector<Index>& PartialCholesky::leading() const { return impl_->leading; }
double PartialCholesky::factor_nonzeros() const { return impl_->common.lnz; }
double PartialCholesky::analysis_s() const { return impl_->analysis_s; }
double PartialCholesky::factorization_s() const { return impl_->factorization_s; }

}  // namespace roifem::solvers
