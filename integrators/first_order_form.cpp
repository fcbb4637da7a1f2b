// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/first_order_form.hpp"

#include <cstring>

#include "model/internal_force.hpp"

namespace roifem::integrators {

FirstOrderForm::FirstOrderForm(const model::SecondOrderSystem& system, Mass mass)
    : system_(system), mass_(mass), force_(system.size()), work_(system.size()), cached_Ku_(system.size()) {
  if (mass_ == Mass::inverted) mass_inverse_ = std::make_unique<model::MassInverse>(system.M);
}

void FirstOrderForm::evaluate(double t, const double* y, double* ydot) {
  const Index n = system_.size();
  const Eigen::Map<const Vector> u(y, n), v(y + n, n);
  Eigen::Map<Vector> du(ydot, n), dv(ydot + n, n);
  system_.load.evaluate(t, force_);
  const bool same_t = cached_t_ == t || !(system_.internal_force && system_.internal_force->has_motion());
  if (!(same_t && cached_u_.size() == n && std::memcmp(cached_u_.data(), y, sizeof(double) * static_cast<std::size_t>(n)) == 0)) {
    cached_u_ = u;
    cached_t_ = t;
    if (system_.internal_force) {
      cached_Ku_.resize(n);
      system_.internal_force->force(t, cached_u_, cached_Ku_);  // f_int(t, u) in place of K u
    } else {
      system_.apply_stiffness(u, cached_Ku_);
    }
  }
  work_ = force_ - cached_Ku_;
  work_.noalias() -= system_.C * v;
  du = v;
  if (mass_ == Mass::kept)
    dv = work_;
  else
    mass_inverse_->apply(work_, dv);
}

const SparseMatrix& FirstOrderForm::stiffness(double t, const double* y) {
  if (!system_.internal_force) return system_.K;
  const Index n = system_.size();
  tangent_u_ = Eigen::Map<const Vector>(y, n);
  tangent_force_.resize(n);
  if (tangent_.nonZeros() != system_.K.nonZeros()) tangent_ = system_.K;  // the pattern, once
  system_.internal_force->force_and_tangent(t, tangent_u_, tangent_force_, tangent_);
  return tangent_;
}

SparseMatrix FirstOrderForm::lower_left(const SparseMatrix& K) const { return -mass_inverse_->apply(K); }
SparseMatrix FirstOrderForm::lower_right() const { return -mass_inverse_->apply(system_.C); }

Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> FirstOrderForm::dense_jacobian() const {
  const Index n = system_.size();
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J = decltype(J)::Zero(2 * n, 2 * n);
  J.topRightCorner(n, n).setIdentity();
  J.bottomLeftCorner(n, n) = -mass_inverse_->apply(DenseMatrix(system_.K));
  J.bottomRightCorner(n, n) = -mass_inverse_->apply(DenseMatrix(system_.C));
  return J;
}

}  // namespace roifem::integrators
