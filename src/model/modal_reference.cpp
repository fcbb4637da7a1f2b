// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/modal_reference.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>
#include <complex>

#include "common/errors.hpp"
#include "model/internal_force.hpp"

namespace roifem::model {

namespace {

using complex = std::complex<double>;

/// The two roots of l^2 + alpha l + w^2 = 0, kept apart at critical damping.
std::pair<complex, complex> roots(double w, double alpha) {
  const double a = alpha / 2;
  complex s = std::sqrt(complex(a * a - w * w, 0.0));
  if (std::abs(s) < 1e-7 * w) s = complex(0.0, 1e-7 * w);  // critical damping: a vanishingly small split
  return {-a + s, -a - s};
}

/// Response from rest to the unit step (slope = false) or the unit slope t H(t) (slope = true),
/// or its time derivative.
double forced(double w, double alpha, double t, bool slope, bool derivative = false) {
  if (t <= 0) return 0.0;
  const auto [l1, l2] = roots(w, alpha);
  const double w2 = w * w;
  const complex A = l2 / (w2 * (l1 - l2)), B = -1.0 / w2 - A;
  if (slope && derivative) return forced(w, alpha, t, false);  // R' = S
  if (derivative) return (A * l1 * std::exp(l1 * t) + B * l2 * std::exp(l2 * t)).real();
  if (!slope) return (1.0 / w2 + A * std::exp(l1 * t) + B * std::exp(l2 * t)).real();
  return (t / w2 + A * (std::exp(l1 * t) - 1.0) / l1 + B * (std::exp(l2 * t) - 1.0) / l2).real();
}

/// Free response from q0, v0, or its time derivative.
double free_response(double w, double alpha, double q0, double v0, double t, bool derivative = false) {
  const auto [l1, l2] = roots(w, alpha);
  const complex C1 = (v0 - l2 * q0) / (l1 - l2), C2 = q0 - C1;
  if (derivative) return (C1 * l1 * std::exp(l1 * t) + C2 * l2 * std::exp(l2 * t)).real();
  return (C1 * std::exp(l1 * t) + C2 * std::exp(l2 * t)).real();
}

}  // namespace

ModalReference::ModalReference(const SecondOrderSystem& system, const State& initial, Index max_dofs) {
  if (system.is_nonlinear())
    throw InputError("modal reference: the exact modal solution exists for a linear model only, and this one is " +
                     system.internal_force->describe());
  const Index n = system.size();
  if (n > max_dofs)
    throw ModelError("modal reference: " + std::to_string(n) + " dofs is more than the dense eigensolver's limit of " +
                     std::to_string(max_dofs));
  for (const auto& term : system.load.terms())
    if (term.ramp.shape != Ramp::Shape::linear)
      throw InputError("modal reference: solves linear ramps only (a load or tool path here is smooth or sampled)");
  const DenseMatrix M(system.M), C(system.C);
  alpha_ = mass_proportional_damping(system);
  if (!std::isfinite(alpha_)) throw InputError("modal reference: needs mass-proportional damping C = alpha M");
  // K phi = w^2 M phi; Eigen normalizes phi^T M phi = I. Lumped or full (Guyan, Craig-Bampton) M.
  const Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> eig(DenseMatrix(system.K), M);
  if (eig.info() != Eigen::Success) throw ModelError("modal reference: the eigensolver failed (is M positive definite?)");
  if (eig.eigenvalues()[0] <= 0) throw ModelError("modal reference: K is not positive definite (a rigid-body mode)");
  omega_ = eig.eigenvalues().cwiseSqrt();
  modes_ = eig.eigenvectors();
  const DenseMatrix phiT_M = modes_.transpose() * M;
  t0_ = initial.t;
  if (t0_ != 0 && !system.load.terms().empty())
    throw InputError("modal reference: a loaded system must start at t = 0 (the ramps' origin)");
  q0_ = phiT_M * initial.u;
  v0_ = phiT_M * initial.v;
  const auto& terms = system.load.terms();
  load_.resize(n, static_cast<Index>(terms.size()));
  for (std::size_t k = 0; k < terms.size(); ++k) {
    load_.col(static_cast<Index>(k)) = modes_.transpose() * terms[k].pattern;
    ramp_duration_.push_back(terms[k].ramp.duration);
  }
}

Vector ModalReference::modal(double t, bool d) const {
  const double tau = t - t0_;
  Vector q(omega_.size());
  for (Index i = 0; i < q.size(); ++i) {
    const double w = omega_[i];
    double value = free_response(w, alpha_, q0_[i], v0_[i], tau, d);
    for (Index k = 0; k < load_.cols(); ++k) {
      const double T = ramp_duration_[static_cast<std::size_t>(k)];
      const double response =
          T > 0 ? (forced(w, alpha_, t, true, d) - forced(w, alpha_, t - T, true, d)) / T : forced(w, alpha_, t, false, d);
      value += load_(i, k) * response;
    }
    q[i] = value;
  }
  return modes_ * q;
}

ModalReference ModalReference::with_ramp(double duration) const {
  if (!(duration >= 0)) throw InputError("modal reference: a ramp's duration must be non-negative");
  ModalReference ramped = *this;
  std::fill(ramped.ramp_duration_.begin(), ramped.ramp_duration_.end(), duration);
  return ramped;
}

Vector ModalReference::displacement(double t) const { return modal(t, false); }
Vector ModalReference::velocity(double t) const { return modal(t, true); }

}  // namespace roifem::model
