// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/modal_elimination.hpp"

#include "common/errors.hpp"
#include "solvers/dense_blas.hpp"

namespace roifem::integrators {

ModalElimination::ModalElimination(const model::SecondOrderSystem& system, double dt) {
  if (!system.modal || !system.damping.is_mass_proportional())
    throw Error("internal: modal elimination needs declared modal coordinates and C = alpha M");
  const double c = 4.0 / (dt * dt) + 2.0 * system.damping.alpha / dt;
  const Index n = system.size(), k = system.modal->count;
  auto& e = *this;
  e.n_d_ = n - k;
  e.c_ = c;
  const auto& M = system.M_split;
  const Index n_i = system.modal->interface_dofs;
  e.interface_.assign(M.index.begin(), M.index.begin() + n_i);
  e.B_ = M.block.topRightCorner(n_i, k);
  e.M_dd_ = M.sparse.topLeftCorner(e.n_d_, e.n_d_);
  const Vector lambda = system.K.diagonal().tail(k);
  e.D_inverse_ = (lambda.array() + c).inverse();
  const DenseMatrix BDBt = e.B_ * e.D_inverse_.asDiagonal() * e.B_.transpose();
  e.interface_operator_ = M.block.topLeftCorner(n_i, n_i) - c * BDBt;

  // K_eff,dd - c^2 B D^-1 B^T, with K_eff = K + c M (C = alpha M folded into c).
  const DenseMatrix correction = (c * c) * BDBt;
  std::vector<Eigen::Triplet<double>> t;
  const SparseMatrix K_eff = system.K + c * system.M;
  t.reserve(static_cast<std::size_t>(K_eff.nonZeros() + correction.size()));
  for (Index j = 0; j < e.n_d_; ++j)
    for (SparseMatrix::InnerIterator it(K_eff, j); it; ++it)
      if (it.row() < e.n_d_) t.emplace_back(it.row(), j, it.value());
  for (Index b = 0; b < n_i; ++b)
    for (Index a = 0; a < n_i; ++a)
      t.emplace_back(e.interface_[static_cast<std::size_t>(a)], e.interface_[static_cast<std::size_t>(b)], -correction(a, b));
  SparseMatrix reduced(e.n_d_, e.n_d_);
  reduced.setFromTriplets(t.begin(), t.end());
  e.factor_.compute(reduced, e.interface_);

  e.r_d_.resize(e.n_d_);
  e.w_i_.resize(n_i);
  e.x_i_.resize(n_i);
  e.product_i_.resize(n_i);
  e.r_q_.resize(k);
  e.y_q_.resize(k);
}

void ModalElimination::solve(const Vector& f, const Vector& w, Vector& x) {
  const Index k = static_cast<Index>(D_inverse_.size()), n_i = static_cast<Index>(interface_.size());
  // With r = f + M w (r_d = f_d + M_dd w_d + B w_q, r_q = f_q + B^T w_I + w_q) the eliminated
  // right-hand side r_d - c B D^-1 r_q is
  //   f_d + M_dd,sparse w_d + (G - c B D^-1 B^T) w_I + B (w_q - c D^-1 (f_q + w_q))
  // (G: M_dd's interface block), and x_q = D^-1 (f_q + w_q + B^T (w_I - c x_I)): B is read once
  // before the solve and once after.
  r_d_.noalias() = M_dd_.transpose() * w.head(n_d_);  // symmetric; row dot products
  r_d_ += f.head(n_d_);
  for (Index a = 0; a < n_i; ++a) w_i_[a] = w[interface_[static_cast<std::size_t>(a)]];
  r_q_ = f.tail(k) + w.tail(k);
  y_q_ = w.tail(k) - c_ * D_inverse_.cwiseProduct(r_q_);
  solvers::multiply_symmetric(interface_operator_, w_i_, 0.0, product_i_);
  solvers::multiply(B_, y_q_, 1.0, product_i_);
  for (Index a = 0; a < n_i; ++a) r_d_[interface_[static_cast<std::size_t>(a)]] += product_i_[a];
  factor_.solve(r_d_, x.head(n_d_));
  for (Index a = 0; a < n_i; ++a) x_i_[a] = w_i_[a] - c_ * x[interface_[static_cast<std::size_t>(a)]];
  solvers::multiply_transposed(B_, x_i_, 1.0, r_q_);
  x.tail(k) = D_inverse_.cwiseProduct(r_q_);
}

}  // namespace roifem::integrators
