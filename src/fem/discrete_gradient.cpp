// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/discrete_gradient.hpp"

#include <cmath>

namespace roifem::fem {

Mat3 green_lagrange(const Mat3& H) { return 0.5 * (H + H.transpose() + H.transpose() * H); }

namespace {

Eigen::Map<const Eigen::Matrix<double, 9, 1>> flat(const Mat3& X) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(X.data());
}

/// S_alg, and with `D` its derivative in E_b, dS_alg = D . vec(dE_b):
///   D = C_mid/2 + c/|dE|^2 1 + vec(dE) (vec(g) - 2 c/|dE|^2 vec(dE))^T / |dE|^2,   dc = g : dE_b.
/// Flattened row-major (Mat3 is column-major: X.data() is X^T's rows; every tensor here is
/// symmetric, so the two flattenings agree).
Mat3 discrete_gradient(const NeoHookean& law, const Mat3& H_a, const Mat3& H_b, Mat9* D) {
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

}  // namespace

Mat3 discrete_gradient_stress(const NeoHookean& law, const Mat3& H_a, const Mat3& H_b) {
  return discrete_gradient(law, H_a, H_b, nullptr);
}

Mat3 discrete_gradient_stress(const NeoHookean& law, const Mat3& H_a, const Mat3& H_b, Mat9& D) {
  return discrete_gradient(law, H_a, H_b, &D);
}

}  // namespace roifem::fem
