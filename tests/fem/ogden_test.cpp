// SPDX-License-Identifier: GPL-3.0-or-later
// The Ogden law (fem/ogden.hpp), each figure against an independent expectation: one term with
// alpha = 2 against the neo-Hookean law; the stress against central differences of the energy,
// the tangents against central differences of the stresses, at general, equal and nearly equal
// principal stretches and at rest; the tangent at rest against the linear law of the same moduli;
// the stress and energy at tiny strain against the linear law (digits kept); compression stiffer
// than tension at alpha = -20; parameters outside their domain refused by name.
#include "fem/ogden.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "fem/neo_hookean.hpp"

namespace roifem::fem {
namespace {

constexpr double ogden_mu = 1000;  // Pa

/// A brain-like two-term law, moderately compressible so that the shear part is visible in the tangent's scale.
Ogden ogden_two_terms() {
  return Ogden({{.mu = 0.7 * ogden_mu, .alpha = -20}, {.mu = 0.3 * ogden_mu, .alpha = 4.5}}, 2 / (10 * ogden_mu));
}

Mat3 ogden_random_gradient(double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Mat3 H;
  for (int i = 0; i < 9; ++i) H(i / 3, i % 3) = scale * u(rng);
  return H;
}

Mat3 ogden_unit(int i, int j) {
  Mat3 e = Mat3::Zero();
  e(i, j) = 1;
  return e;
}

/// The gradients the checks run at: general, equal and nearly equal principal stretches, rest.
std::vector<std::pair<std::string, Mat3>> ogden_gradients() {
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  auto symmetric = [&](double a, double b, double c) { return Mat3(R * Vec3(a, b, c).asDiagonal() * R.transpose()); };
  return {{"general", ogden_random_gradient(0.15, 1)},
          {"general, large", ogden_random_gradient(0.35, 2)},
          {"three equal stretches", symmetric(0.1, 0.1, 0.1)},
          {"two equal stretches", symmetric(-0.12, 0.05, 0.05)},
          {"two nearly equal stretches", symmetric(-0.12, 0.05, 0.05 + 1e-9)},
          {"rest", Mat3::Zero()}};
}

double ogden_largest(const auto& m) { return m.cwiseAbs().maxCoeff(); }

TEST(Ogden, OneTermWithAlphaTwoIsTheNeoHookeanLaw) {
  const NeoHookean neo{.C10 = ogden_mu / 2, .D1 = 2 / (20 * ogden_mu)};
  const Ogden ogden({{.mu = ogden_mu, .alpha = 2}}, neo.D1);
  for (const auto& [name, H] : ogden_gradients()) {
    SCOPED_TRACE(name);
    EXPECT_NEAR(ogden.energy(H), neo.energy(H), 1e-12 * std::max(1.0, neo.energy(H)));
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    EXPECT_LE(ogden_largest(ogden.stress_of_strain(E) - neo.stress_of_strain(E)), 1e-11 * ogden_mu);
    EXPECT_LE(ogden_largest(ogden.strain_tangent(E) - neo.strain_tangent(E)), 1e-11 * 20 * ogden_mu);
    Mat3 P_o, P_n;
    Mat9 A_o, A_n;
    ogden.stress_and_tangent(H, P_o, A_o);
    neo.stress_and_tangent(H, P_n, A_n);
    EXPECT_LE(ogden_largest(P_o - P_n), 1e-11 * ogden_mu);
    EXPECT_LE(ogden_largest(A_o - A_n), 1e-11 * 20 * ogden_mu);
  }
}

TEST(Ogden, StressIsTheEnergysDerivativeAndTheTangentsTheStressesAtEveryKindOfStretch) {
  const Ogden law = ogden_two_terms();
  const double h = 1e-6;
  for (const auto& [name, H] : ogden_gradients()) {
    SCOPED_TRACE(name);
    Mat3 P;
    Mat9 A;
    law.stress_and_tangent(H, P, A);
    EXPECT_TRUE(P.allFinite() && A.allFinite());
    EXPECT_LE(ogden_largest(P - law.stress(H)), 1e-12 * ogden_mu);
    Mat3 P_fd;
    Mat9 A_fd;
    for (int k = 0; k < 3; ++k)
      for (int L = 0; L < 3; ++L) {
        P_fd(k, L) = (law.energy(H + h * ogden_unit(k, L)) - law.energy(H - h * ogden_unit(k, L))) / (2 * h);
        const Mat3 dP = (law.stress(H + h * ogden_unit(k, L)) - law.stress(H - h * ogden_unit(k, L))) / (2 * h);
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J) A_fd(3 * i + J, 3 * k + L) = dP(i, J);
      }
    EXPECT_LE(ogden_largest(P_fd - P), 1e-6 * std::max(ogden_largest(P), ogden_mu)) << "P\n" << P << "\nby differences\n" << P_fd;
    EXPECT_LE(ogden_largest(A_fd - A), 1e-6 * ogden_largest(A));
    // dS/dE against differences of S along symmetric strains.
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    const Mat9 D = law.strain_tangent(E);
    for (int K = 0; K < 3; ++K)
      for (int L = K; L < 3; ++L) {
        const Mat3 dE = 0.5 * (ogden_unit(K, L) + ogden_unit(L, K));
        const Mat3 dS = (law.stress_of_strain(E + h * dE) - law.stress_of_strain(E - h * dE)) / (2 * h);
        const Eigen::Matrix<double, 9, 1> predicted =
            D * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Mat3(dE.transpose()).data());
        for (int I = 0; I < 3; ++I)
          for (int J = 0; J < 3; ++J) EXPECT_NEAR(predicted[3 * I + J], dS(I, J), 1e-6 * ogden_largest(D)) << I << J << K << L;
      }
    EXPECT_LE(ogden_largest(D - D.transpose()), 1e-12 * ogden_largest(D));
  }
}

TEST(Ogden, NearlyEqualStretchesGiveTheTangentOfEqualOnesToTheirDistance) {
  // Divided differences formed naively, (g(x) - g(y)) / (x - y), lose half the digits at a distance
  // of 1e-10; the law's are exact to rounding, so the tangents differ by O(1e-10) only.
  const Ogden law = ogden_two_terms();
  const Mat3 R = Eigen::AngleAxisd(0.3, Vec3(0, 1, 1).normalized()).toRotationMatrix();
  for (const double gap : {1e-10, 1e-13, 1e-15}) {
    const Mat3 equal = R * Vec3(-0.1, 0.04, 0.04).asDiagonal() * R.transpose();
    const Mat3 nearly = R * Vec3(-0.1, 0.04, 0.04 + gap).asDiagonal() * R.transpose();
    Mat3 P1, P2;
    Mat9 A1, A2;
    law.stress_and_tangent(equal, P1, A1);
    law.stress_and_tangent(nearly, P2, A2);
    EXPECT_LE(ogden_largest(A1 - A2), (1e-13 + 10 * gap) * ogden_largest(A1)) << "gap " << gap;
  }
}

TEST(Ogden, TangentAtRestIsTheLinearLawWithTheSameModuli) {
  const Ogden law = ogden_two_terms();
  const double mu = law.mu(), lambda = law.kappa() - 2.0 / 3.0 * mu;
  EXPECT_DOUBLE_EQ(mu, ogden_mu);
  Mat3 P;
  Mat9 A;
  law.stress_and_tangent(Mat3::Zero(), P, A);
  EXPECT_EQ(ogden_largest(P), 0.0);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const double linear = lambda * (i == J) * (k == L) + mu * ((i == k) * (J == L) + (i == L) * (J == k));
          EXPECT_NEAR(A(3 * i + J, 3 * k + L), linear, 1e-12 * law.kappa());
        }
}

TEST(Ogden, KeepsItsDigitsAtTinyStrainWhereItIsTheLinearLaw) {
  const Ogden law = ogden_two_terms();
  const double mu = law.mu(), lambda = law.kappa() - 2.0 / 3.0 * mu;
  for (const double scale : {1e-7, 1e-10, 1e-13}) {
    const Mat3 H = ogden_random_gradient(scale, 7);
    const Mat3 eps = 0.5 * (H + H.transpose());
    const Mat3 linear = lambda * eps.trace() * Mat3::Identity() + 2 * mu * eps;
    // The law's own departure is O(alpha |H|) relative; rounding in a cancelling form would be O(1e-16 / |H|).
    EXPECT_LE(ogden_largest(law.stress(H) - linear), 100 * scale * ogden_largest(linear)) << scale;
    const double W_linear = 0.5 * lambda * eps.trace() * eps.trace() + mu * (eps.array() * eps.array()).sum();
    EXPECT_NEAR(law.energy(H), W_linear, 100 * scale * W_linear) << scale;
  }
}

TEST(Ogden, AlphaMinusTwentyIsStifferInCompressionThanInTension) {
  // A homogeneous uniaxial stretch l along x with the lateral stretch that frees the lateral
  // stress (found by bisection on the law's own P): |P_xx| at l = 0.9 against l = 1.1.
  const Ogden law({{.mu = ogden_mu, .alpha = -20}}, 2 / (1000 * ogden_mu));
  auto axial = [&](double l) {
    double lo = 0.5, hi = 1.5;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (lo + hi);
      const Mat3 H = Vec3(l - 1, m - 1, m - 1).asDiagonal();
      (law.stress(H)(1, 1) > 0 ? hi : lo) = m;
    }
    const double m = 0.5 * (lo + hi);
    return law.stress(Mat3(Vec3(l - 1, m - 1, m - 1).asDiagonal()))(0, 0);
  };
  const double compression = -axial(0.9), tension = axial(1.1);
  EXPECT_GT(tension, 0);
  EXPECT_GT(compression / tension, 2.5) << "compression " << compression << " Pa, tension " << tension << " Pa";
}

TEST(Ogden, RefusesParametersOutsideTheirDomainByName) {
  auto refusal = [](std::vector<OgdenTerm> terms, double D1) {
    try {
      Ogden(std::move(terms), D1);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal({}, 1e-3), "Ogden law: no term (give mu and alpha for at least one)");
  EXPECT_EQ(refusal({{.mu = 1000, .alpha = -20}, {.mu = -1, .alpha = 2}}, 1e-3),
            "Ogden law, term 2: mu = -1 Pa (it must be positive and finite)");
  EXPECT_EQ(refusal({{.mu = 1000, .alpha = 0}}, 1e-3), "Ogden law, term 1: alpha = 0 (it must be finite and not 0)");
  EXPECT_EQ(refusal({{.mu = 1000, .alpha = 2}}, 0), "Ogden law: D1 = 0 1/Pa (it must be positive and finite)");
  EXPECT_EQ(refusal({{.mu = 1000, .alpha = 2}}, 1e-3), "accepted");
}

}  // namespace
}  // namespace roifem::fem
