// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/discrete_gradient.hpp"

#include "fem/ogden.hpp"

#include <cmath>

namespace roifem::fem {

Mat3 green_lagrange(const Mat3& H) { return 0.5 * (H + H.transpose() + H.transpose() * H); }

namespace {

Eigen::Map<const Eigen::Matrix<double, 9, 1>> flat(const Mat3& X) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(X.data());
}

/// Gonzalez's projected discrete gradient of `law` (the deviatoric part below), and with `D` its
/// derivative in E_b, dS_alg = D . vec(dE_b):
///   D = C_mid/2 + c/|dE|^2 1 + vec(dE) (vec(g) - 2 c/|dE|^2 vec(dE))^T / |dE|^2,   dc = g : dE_b.
/// Flattened row-major (Mat3 is column-major: X.data() is X^T's rows; every tensor here is
/// symmetric, so the two flattenings agree).
template <class Law>
Mat3 projected_discrete_gradient(const Law& law, const Mat3& H_a, const Mat3& H_b, Mat9* D) {
  const Mat3 E_a = green_lagrange(H_a), E_b = green_lagrange(H_b);
  const Mat3 dE = E_b - E_a;
  const Mat3 E_mid = 0.5 * (E_a + E_b);
  Mat3 S_mid = law.stress_of_strain(E_mid);  // not const: returned below where dE is negligible
  Mat9 C_mid;
  if (D) C_mid = law.strain_tangent(E_mid);
  const double dE2 = dE.squaredNorm();
  if (dE2 < negligible_increment * negligible_increment) {
    if (D) *D = 0.5 * C_mid;
    return S_mid;
  }
  // c = W(b) - W(a) - S_mid : dE, O(|dE|^3), and its gradient g in E_b.
  double c = 0;
  Eigen::Matrix<double, 9, 1> g;
  if (dE2 >= large_increment * large_increment) {
    c = law.energy(H_b) - law.energy(H_a) - S_mid.cwiseProduct(dE).sum();
    if (D) g = flat(law.stress_of_strain(E_b)) - flat(S_mid) - 0.5 * C_mid.transpose() * flat(dE);
  } else {
    // c = int_0^1 (S(E_a + s dE) - S_mid) : dE ds by 3-point Gauss-Legendre (its middle point is
    // E_mid, where the integrand vanishes); C = I + 2E stays positive definite along the segment,
    // a convex combination of C_a and C_b. The points E_mid -+ h dE move by (1/2 -+ h) dE_b.
    const double h = 0.5 * std::sqrt(0.6);
    const Mat3 E_minus = E_mid - h * dE, E_plus = E_mid + h * dE;
    const Mat3 dS = law.stress_of_strain(E_minus) + law.stress_of_strain(E_plus) - 2 * S_mid;
    c = (5.0 / 18.0) * dS.cwiseProduct(dE).sum();
    if (D) {
      const Mat9 dC = (0.5 - h) * law.strain_tangent(E_minus) + (0.5 + h) * law.strain_tangent(E_plus) - C_mid;
      g = (5.0 / 18.0) * (dC.transpose() * flat(dE) + flat(dS));
    }
  }
  const double ratio = c / dE2;
  if (D) {
    *D = 0.5 * C_mid + ratio * Mat9::Identity();
    D->noalias() += flat(dE) * ((g - 2 * ratio * flat(dE)) / dE2).transpose();
  }
  return S_mid + ratio * dE;
}

/// The cofactor matrix of a symmetric C: det C C^-1, with no division.
Mat3 symmetric_cofactor(const Mat3& C) {
  Mat3 X;
  X(0, 0) = C(1, 1) * C(2, 2) - C(1, 2) * C(2, 1);
  X(1, 1) = C(0, 0) * C(2, 2) - C(0, 2) * C(2, 0);
  X(2, 2) = C(0, 0) * C(1, 1) - C(0, 1) * C(1, 0);
  X(0, 1) = X(1, 0) = C(1, 2) * C(2, 0) - C(1, 0) * C(2, 2);
  X(0, 2) = X(2, 0) = C(1, 0) * C(2, 1) - C(1, 1) * C(2, 0);
  X(1, 2) = X(2, 1) = C(0, 2) * C(1, 0) - C(0, 0) * C(1, 2);
  return X;
}

/// d cof(C) / dC over symmetric increments: det C (C^-1 x C^-1 - C^-1 o C^-1), flattened as
/// NeoHookean::strain_tangent.
Mat9 cofactor_derivative(const Mat3& C) {
  const double det = C.determinant();
  const Mat3 G = C.inverse();
  Mat9 T;
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J)
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L)
          T(3 * I + J, 3 * K + L) = det * (G(I, J) * G(K, L) - 0.5 * (G(I, K) * G(J, L) + G(I, L) * G(J, K)));
  return T;
}

/// The volumetric part's discrete gradient, added to S (and its derivative to D):
///   S_vol,alg = kappa (J_mid - 1) / J_mid G,   G = (cof C_a + 4 cof C_mid + cof C_b) / 6,
/// J_mid = (J_a + J_b)/2, C_mid = (C_a + C_b)/2 (see the header).
template <class Law>
void add_volumetric_discrete_gradient(const Law& law, const Mat3& H_a, const Mat3& H_b, Mat3& S, Mat9* D) {
  const double kappa = law.kappa();
  const Mat3 F_a = Mat3::Identity() + H_a, F_b = Mat3::Identity() + H_b;
  const Mat3 C_a = F_a.transpose() * F_a, C_b = F_b.transpose() * F_b, C_mid = 0.5 * (C_a + C_b);
  const double J_b_minus_1 = NeoHookean::J_minus_1(H_b);
  const double J_mid_minus_1 = 0.5 * (NeoHookean::J_minus_1(H_a) + J_b_minus_1), J_mid = 1 + J_mid_minus_1;
  const Mat3 G = (symmetric_cofactor(C_a) + 4 * symmetric_cofactor(C_mid) + symmetric_cofactor(C_b)) / 6;
  const double phi = J_mid_minus_1 / J_mid;
  S += kappa * phi * G;
  if (!D) return;
  // d phi = dJ_mid / J_mid^2, dJ_mid = J_b C_b^-1 : dE_b / 2; dC_mid = dE_b, dC_b = 2 dE_b.
  const Mat3 dJ_mid = 0.5 * (1 + J_b_minus_1) * C_b.inverse();
  D->noalias() += kappa / (J_mid * J_mid) * flat(G) * flat(dJ_mid).transpose();
  D->noalias() += kappa * phi / 3 * (2 * cofactor_derivative(C_mid) + cofactor_derivative(C_b));
}

/// S_alg: the deviatoric part by Gonzalez's projection, the volumetric part by its own.
template <class Law>
Mat3 discrete_gradient(const Law& law, const Mat3& H_a, const Mat3& H_b, Mat9* D) {
  Mat3 S = projected_discrete_gradient(law.deviatoric_part(), H_a, H_b, D);  // kappa = 0
  add_volumetric_discrete_gradient(law, H_a, H_b, S, D);
  return S;
}

}  // namespace

template <class Law>
Mat3 discrete_gradient_stress(const Law& law, const Mat3& H_a, const Mat3& H_b) {
  return discrete_gradient(law, H_a, H_b, nullptr);
}

template <class Law>
Mat3 discrete_gradient_stress(const Law& law, const Mat3& H_a, const Mat3& H_b, Mat9& D) {
  return discrete_gradient(law, H_a, H_b, &D);
}

template Mat3 discrete_gradient_stress(const NeoHookean&, const Mat3&, const Mat3&);
template Mat3 discrete_gradient_stress(const NeoHookean&, const Mat3&, const Mat3&, Mat9&);
template Mat3 discrete_gradient_stress(const Ogden&, const Mat3&, const Mat3&);
template Mat3 discrete_gradient_stress(const Ogden&, const Mat3&, const Mat3&, Mat9&);

}  // namespace roifem::fem
