// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/neo_hookean.hpp"

#include <cmath>

namespace roifem::fem {

namespace {

/// The strain measures of F = I + H, each formed from H without cancellation.
struct NeoHookeanStrain {
  double J_minus_1 = 0;
  Mat3 dev_C;                ///< dev(C) = dev(2E), 2E = H + H^T + H^T H
  double I1_minus_3J23 = 0;  ///< tr C - 3 J^(2/3) >= 0 (I1bar - 3 = J^(-2/3) times it)
};

/// h(d) = 3 ((1 + d)^(1/3) - 1) - d = O(d^2): its series where direct evaluation would cancel.
double cube_root_remainder(double d) {
  if (std::abs(d) > 0.05) return 3 * std::expm1(std::log1p(d) / 3) - d;
  // 3 sum_{k >= 2} binom(1/3, k) d^k; at |d| <= 0.05 the terms after k = 14 are below 1e-16 of the first.
  double term = 1.0 / 3.0 * d, sum = 0;  // binom(1/3, 1) d
  for (int k = 2; k <= 14; ++k) {
    term *= (1.0 / 3.0 - (k - 1)) / k * d;
    sum += term;
  }
  return 3 * sum;
}

/// The strain measures; `with_invariant`: I1_minus_3J23 too (the energy's; the stresses need
/// only J - 1 and dev C).
NeoHookeanStrain strain_of(const Mat3& H, bool with_invariant = false) {
  NeoHookeanStrain s;
  s.J_minus_1 = NeoHookean::J_minus_1(H);
  const Mat3 twice_E = H + H.transpose() + H.transpose() * H;
  const double tr2E = twice_E.trace();
  s.dev_C = twice_E - tr2E / 3 * Mat3::Identity();
  if (!with_invariant) return s;
  // det C = 1 + 2 tr E + 2 ((tr E)^2 - tr E^2) + 8 det E, so with delta = det C - 1 = J^2 - 1:
  //   tr C - 3 (1 + delta)^(1/3) = -2 ((tr E)^2 - tr E^2) - 8 det E - h(delta).
  const Mat3 E = 0.5 * twice_E;
  const double trE = E.trace();
  const double delta = s.J_minus_1 * (2 + s.J_minus_1);
  s.I1_minus_3J23 = -2 * (trE * trE - (E * E).trace()) - 8 * E.determinant() - cube_root_remainder(delta);
  return s;
}

}  // namespace

NeoHookean NeoHookean::of(const Material& m) {
  const double kappa = m.lambda + 2.0 * m.mu / 3.0;
  return {.C10 = m.mu / 2, .D1 = 2 / kappa};
}

double NeoHookean::J_minus_1(const Mat3& H) {
  const double tr = H.trace();
  return tr + 0.5 * (tr * tr - (H * H).trace()) + H.determinant();
}

double NeoHookean::energy(const Mat3& H) const {
  const NeoHookeanStrain s = strain_of(H, true);
  const double a = std::exp(-2.0 / 3.0 * std::log1p(s.J_minus_1));  // J^(-2/3)
  return C10 * a * s.I1_minus_3J23 + s.J_minus_1 * s.J_minus_1 / D1;
}

Mat3 NeoHookean::stress(const Mat3& H) const {
  const NeoHookeanStrain s = strain_of(H);
  const double J = 1 + s.J_minus_1;
  const Mat3 S = 2 * C10 * std::pow(J, -2.0 / 3.0) * s.dev_C + 2 / D1 * s.J_minus_1 * J * Mat3::Identity();
  return (Mat3::Identity() + H).inverse().transpose() * S;
}

Mat3 NeoHookean::excess_stress(const Mat3& H) const {
  const double mu = 2 * C10, lambda = 2 / D1 - 2.0 / 3.0 * mu;
  return stress(H) - (lambda * H.trace() * Mat3::Identity() + mu * (H + H.transpose()));
}

// With a = J^(-2/3), G = F^-1 and the derivatives dJ/dF_kL = J G_Lk, dG_Ji/dF_kL = -G_Jk G_Li:
//   P_iJ = 2 C10 a (F_iJ - I1/3 G_Ji) + 2/D1 (J^2 - J) G_Ji
//   dP_iJ/dF_kL = 2 C10 a [d_ik d_JL - 2/3 F_iJ G_Lk - 2/3 G_Ji F_kL + 2/9 I1 G_Ji G_Lk + I1/3 G_Jk G_Li]
//               + 2/D1 [(2J - 1) J G_Ji G_Lk - (J^2 - J) G_Jk G_Li]
// The tangent is O(mu) and needs no care; P is formed as stress() forms it.
void NeoHookean::stress_and_tangent(const Mat3& H, Mat3& P, Mat9& A) const {
  const NeoHookeanStrain s = strain_of(H);
  const Mat3 F = Mat3::Identity() + H;
  const double J = 1 + s.J_minus_1;
  const Mat3 G = F.inverse();
  const double a = std::pow(J, -2.0 / 3.0), I1 = F.squaredNorm();
  const double shear = 2 * C10 * a, bulk = 2 / D1;
  P = G.transpose() * (shear * s.dev_C + bulk * s.J_minus_1 * J * Mat3::Identity());
  const double c_GG = shear * 2.0 / 9.0 * I1 + bulk * (2 * J - 1) * J;  // G_Ji G_Lk
  const double c_GGx = shear * I1 / 3.0 - bulk * (J * J - J);           // G_Jk G_Li
  for (int i = 0; i < 3; ++i)
    for (int Jc = 0; Jc < 3; ++Jc)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double v = c_GG * G(Jc, i) * G(L, k) + c_GGx * G(Jc, k) * G(L, i) -
                     shear * 2.0 / 3.0 * (F(i, Jc) * G(L, k) + G(Jc, i) * F(k, L));
          if (i == k && Jc == L) v += shear;
          A(3 * i + Jc, 3 * k + L) = v;
        }
}

namespace {

/// The measures of C = I + 2E that stress_of_strain and strain_tangent share.
struct StrainOfC {
  double J = 1, J_minus_1 = 0, tr2E = 0;
  Mat3 C_inverse;
};

StrainOfC strain_of_C(const Mat3& E) {
  const Mat3 twice_E = 2 * E;
  StrainOfC s;
  s.tr2E = twice_E.trace();
  // det C - 1 = J^2 - 1 with C = I + 2E, as J_minus_1 forms det(I + H) - 1.
  const double delta = s.tr2E + 0.5 * (s.tr2E * s.tr2E - (twice_E * twice_E).trace()) + twice_E.determinant();
  s.J = std::sqrt(1 + delta);
  s.J_minus_1 = delta / (s.J + 1);
  s.C_inverse = (Mat3::Identity() + twice_E).inverse();
  return s;
}

}  // namespace

Mat9 NeoHookean::strain_tangent(const Mat3& E) const {
  const StrainOfC s = strain_of_C(E);
  const Mat3& G = s.C_inverse;
  const double I1 = 3 + s.tr2E;
  const double shear = 2.0 / 3.0 * 2 * C10 * std::pow(s.J, -2.0 / 3.0), bulk = 2 / D1;
  Mat9 D;
  for (int I = 0; I < 3; ++I)
    for (int Jc = 0; Jc < 3; ++Jc)
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L) {
          const double GoG = 0.5 * (G(I, K) * G(Jc, L) + G(I, L) * G(Jc, K));
          const double GxG = G(I, Jc) * G(K, L);
          const double GxI = K == L ? G(I, Jc) : 0.0, IxG = I == Jc ? G(K, L) : 0.0;
          D(3 * I + Jc, 3 * K + L) =
              shear * (I1 * GoG - GxI - IxG + I1 / 3 * GxG) + bulk * ((2 * s.J - 1) * s.J * GxG - 2 * s.J_minus_1 * s.J * GoG);
        }
  return D;
}

Mat3 NeoHookean::stress_of_strain(const Mat3& E) const {
  const Mat3 twice_E = 2 * E;
  const double tr2E = twice_E.trace();
  // det C - 1 = J^2 - 1 with C = I + 2E, as J_minus_1 forms det(I + H) - 1.
  const double delta = tr2E + 0.5 * (tr2E * tr2E - (twice_E * twice_E).trace()) + twice_E.determinant();
  const double J = std::sqrt(1 + delta), J_minus_1 = delta / (J + 1);
  const Mat3 C_inverse = (Mat3::Identity() + twice_E).inverse();
  const Mat3 dev_C = twice_E - tr2E / 3 * Mat3::Identity();
  const Mat3 S = C_inverse * (2 * C10 * std::pow(J, -2.0 / 3.0) * dev_C + 2 / D1 * J_minus_1 * J * Mat3::Identity());
  return 0.5 * (S + S.transpose());  // C^-1 dev C = I - I1/3 C^-1 is symmetric; rounding is not
}

}  // namespace roifem::fem
