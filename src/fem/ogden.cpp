// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/ogden.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::fem {

namespace {

/// E = N diag(e) N^T: the eigenvalues and orthonormal eigenvectors (columns) of a symmetric E.
struct StrainSpectrum {
  Vec3 e;
  Mat3 N;
};

StrainSpectrum strain_spectrum(const Mat3& E) {
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(0.5 * (E + E.transpose()));
  return {solver.eigenvalues(), solver.eigenvectors()};
}

/// g_p(e) = (1 + 2e)^p - 1, its derivative and its divided difference g_p[x, y].
double power_less_one(double p, double e) { return std::expm1(p * std::log1p(2 * e)); }
double power_slope(double p, double e) { return 2 * p * std::exp((p - 1) * std::log1p(2 * e)); }
double power_divided(double p, double x, double y) {
  // (c_x^p - c_y^p) / (x - y) = 2 c_y^(p - 1) (r^p - 1) / (r - 1), r = c_x / c_y = e^t.
  const double t = std::log1p(2 * (x - y) / (1 + 2 * y));
  const double ratio = t == 0 ? p : std::expm1(p * t) / std::expm1(t);
  return 2 * std::exp((p - 1) * std::log1p(2 * y)) * ratio;
}

/// G_p = C^p - I.
Mat3 power_less_identity(const StrainSpectrum& s, double p) {
  Mat3 G = Mat3::Zero();
  for (int k = 0; k < 3; ++k) G += power_less_one(p, s.e[k]) * s.N.col(k) * s.N.col(k).transpose();
  return G;
}

/// sum_k g_p'(e_k) N_k N_k^T: the gradient of tr G_p with respect to E.
Mat3 trace_gradient(const StrainSpectrum& s, double p) {
  Mat3 D = Mat3::Zero();
  for (int k = 0; k < 3; ++k) D += power_slope(p, s.e[k]) * s.N.col(k) * s.N.col(k).transpose();
  return D;
}

/// dG_p/dE by Daleckii and Krein, minor-symmetrized (entry (I, J; K, L) at 3 I + J, 3 K + L).
Mat9 power_derivative(const StrainSpectrum& s, double p) {
  Mat3 dd;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) dd(k, l) = k == l ? power_slope(p, s.e[k]) : power_divided(p, s.e[k], s.e[l]);
  Mat9 D = Mat9::Zero();
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const Vec3 a = s.N.col(k), b = s.N.col(l);
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J)
          for (int K = 0; K < 3; ++K)
            for (int L = 0; L < 3; ++L) D(3 * I + J, 3 * K + L) += dd(k, l) * a[I] * b[J] * 0.5 * (a[K] * b[L] + a[L] * b[K]);
    }
  return D;
}

/// J - 1 and J of C = I + 2E, with det C - 1 formed as NeoHookean::J_minus_1 forms det(I + H) - 1.
std::pair<double, double> volume_ratio_of_strain(const Mat3& E) {
  const Mat3 twice_E = 2 * E;
  const double tr = twice_E.trace();
  const double delta = tr + 0.5 * (tr * tr - (twice_E * twice_E).trace()) + twice_E.determinant();
  const double J = std::sqrt(1 + delta);
  return {delta / (J + 1), J};
}

Mat9 dyadic(const Mat3& A, const Mat3& B) {
  Mat9 D;
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J)
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L) D(3 * I + J, 3 * K + L) = A(I, J) * B(K, L);
  return D;
}

/// phi(x) = e^x - 1 - x >= 0, by its series where the difference would cancel.
double expm1_less_identity(double x) {
  if (std::abs(x) >= 0.1) return std::expm1(x) - x;
  double term = x, sum = 0;
  for (int n = 2; n <= 14; ++n) {  // at |x| < 0.1 the terms after n = 14 are below 1e-16 of the first
    term *= x / n;
    sum += term;
  }
  return sum;
}

}  // namespace

Ogden::Ogden(std::vector<OgdenTerm> terms, double D1) : terms_(std::move(terms)), D1_(D1) {
  if (terms_.empty()) throw InputError("Ogden law: no term (give mu and alpha for at least one)");
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const std::string which = "Ogden law, term " + std::to_string(i + 1) + ": ";
    if (!(terms_[i].mu > 0) || !std::isfinite(terms_[i].mu))
      throw InputError(which + "mu = " + number_text(terms_[i].mu) + " Pa (it must be positive and finite)");
    if (terms_[i].alpha == 0 || !std::isfinite(terms_[i].alpha))
      throw InputError(which + "alpha = " + number_text(terms_[i].alpha) + " (it must be finite and not 0)");
  }
  if (!(D1_ > 0) || !std::isfinite(D1_))
    throw InputError("Ogden law: D1 = " + number_text(D1_) + " 1/Pa (it must be positive and finite)");
}

Ogden Ogden::of(const Material& material) { return {material.ogden, 2 / (material.lambda + 2 * material.mu / 3)}; }

Ogden Ogden::deviatoric_part() const {
  Ogden deviatoric = *this;
  deviatoric.D1_ = std::numeric_limits<double>::infinity();
  return deviatoric;
}

double Ogden::mu() const {
  double sum = 0;
  for (const OgdenTerm& t : terms_) sum += t.mu;
  return sum;
}

double Ogden::energy(const Mat3& H) const {
  const double J_minus_1 = NeoHookean::J_minus_1(H);
  const StrainSpectrum s = strain_spectrum(0.5 * (H + H.transpose() + H.transpose() * H));
  // d_k = log lambda_k - log J / 3, their sum (zero exactly) made zero in rounding too.
  Vec3 d;
  for (int k = 0; k < 3; ++k) d[k] = 0.5 * std::log1p(2 * s.e[k]) - std::log1p(J_minus_1) / 3;
  d.array() -= d.sum() / 3;
  double W = J_minus_1 * J_minus_1 / D1_;
  for (const OgdenTerm& t : terms_) {
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += expm1_less_identity(t.alpha * d[k]);
    W += 2 * t.mu / (t.alpha * t.alpha) * sum;
  }
  return W;
}

Mat3 Ogden::stress_of_strain(const Mat3& E) const {
  const auto [J_minus_1, J] = volume_ratio_of_strain(E);
  const StrainSpectrum s = strain_spectrum(E);
  const Mat3 G_inverse = power_less_identity(s, -1);  // C^-1 - I
  const Mat3 C_inverse = Mat3::Identity() + G_inverse;
  Mat3 S = 2 / D1_ * J_minus_1 * J * C_inverse;
  for (const OgdenTerm& t : terms_) {
    const double a = t.alpha / 2, c = std::exp(-t.alpha / 3 * std::log1p(J_minus_1));
    const double T = power_less_identity(s, a).trace();  // tr C^a - 3
    const Mat3 B = power_less_identity(s, a - 1) - G_inverse - T / 3 * C_inverse;
    S += 2 * t.mu / t.alpha * c * B;
  }
  return 0.5 * (S + S.transpose());
}

Mat9 Ogden::strain_tangent(const Mat3& E) const {
  const auto [J_minus_1, J] = volume_ratio_of_strain(E);
  const StrainSpectrum s = strain_spectrum(E);
  const Mat3 G_inverse = power_less_identity(s, -1);
  const Mat3 C_inverse = Mat3::Identity() + G_inverse;
  const Mat9 dG_inverse = power_derivative(s, -1);
  // The volumetric part: kappa [(2J - 1) J C^-1 x C^-1 + 2 (J - 1) J dC^-1/dE], dC^-1/dE = dG_-1/dE.
  const double kappa = 2 / D1_;
  Mat9 D = kappa * ((2 * J - 1) * J * dyadic(C_inverse, C_inverse) + J_minus_1 * J * dG_inverse);
  for (const OgdenTerm& t : terms_) {
    const double a = t.alpha / 2, c = std::exp(-t.alpha / 3 * std::log1p(J_minus_1));
    const double T = power_less_identity(s, a).trace();
    const Mat3 B = power_less_identity(s, a - 1) - G_inverse - T / 3 * C_inverse;
    // S_i = k c B: dc = -(alpha/3) c C^-1 : dE, dT = trace_gradient : dE.
    const Mat9 dB = power_derivative(s, a - 1) - dG_inverse - dyadic(C_inverse, trace_gradient(s, a)) / 3 - T / 3 * dG_inverse;
    D += 2 * t.mu / t.alpha * c * (dB - t.alpha / 3 * dyadic(B, C_inverse));
  }
  return 0.5 * (D + D.transpose());
}

Mat3 Ogden::stress(const Mat3& H) const {
  return (Mat3::Identity() + H) * stress_of_strain(0.5 * (H + H.transpose() + H.transpose() * H));
}

Mat3 Ogden::excess_stress(const Mat3& H) const {
  const double shear = mu(), lambda = kappa() - 2.0 / 3.0 * shear;
  return stress(H) - (lambda * H.trace() * Mat3::Identity() + shear * (H + H.transpose()));
}

// P_iJ = F_iI S_IJ, dS_IJ = D_IJKL dE_KL, dE_KL = sym(F^T dF)_KL:
//   dP_iJ/dF_kL = d_ik S_LJ + sum_{I,M} F_iI D_(IJ)(ML) F_kM.
void Ogden::stress_and_tangent(const Mat3& H, Mat3& P, Mat9& A) const {
  const Mat3 F = Mat3::Identity() + H;
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
  const Mat3 S = stress_of_strain(E);
  const Mat9 D = strain_tangent(E);
  P = F * S;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double v = i == k ? S(L, J) : 0.0;
          for (int I = 0; I < 3; ++I)
            for (int M = 0; M < 3; ++M) v += F(i, I) * D(3 * I + J, 3 * M + L) * F(k, M);
          A(3 * i + J, 3 * k + L) = v;
        }
}

}  // namespace roifem::fem
