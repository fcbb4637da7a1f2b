// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/tet4.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

namespace roifem::fem {
namespace {

const Material rubber = Material::from_young_poisson(1e4, 0.3, 1000, 0);

TEST(Tet4Element, StiffnessIsSymmetricPositiveSemidefiniteWithSixRigidModes) {
  const Tet4Geometry g = tet4_geometry({0.1, 0.0, 0.0}, {1.3, 0.2, -0.1}, {0.2, 0.9, 0.3}, {0.0, 0.1, 1.1});
  ASSERT_GT(g.volume, 0);
  const ElementMatrix K = tet4_stiffness(g, rubber);
  EXPECT_LE((K - K.transpose()).norm(), 1e-13 * K.norm());
  const Eigen::SelfAdjointEigenSolver<ElementMatrix> eig(K);
  const auto& lambda = eig.eigenvalues();  // ascending
  const double largest = lambda.maxCoeff();
  int zeros = 0;
  for (int i = 0; i < 12; ++i) {
    EXPECT_GT(lambda[i], -1e-12 * largest) << "eigenvalue " << i;
    if (std::abs(lambda[i]) < 1e-10 * largest) ++zeros;
  }
  EXPECT_EQ(zeros, 6);
  EXPECT_GT(lambda[6], 1e-4 * largest);  // the six deformation modes are clearly non-zero
}

TEST(Tet4Element, RigidBodyMotionsProduceNoForce) {
  const Vec3 x[4] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 0.8}};
  const ElementMatrix K = tet4_stiffness(tet4_geometry(x[0], x[1], x[2], x[3]), rubber);
  const Vec3 translation(0.3, -0.2, 0.5), omega(0.1, 0.4, -0.7);
  Eigen::Matrix<double, 12, 1> u;
  for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = translation + omega.cross(x[a]);  // infinitesimal rotation
  EXPECT_LE((K * u).norm(), 1e-12 * K.norm() * u.norm());
}

TEST(Tet4Element, StrainOfAnAffineFieldIsItsSymmetricGradient) {
  const Vec3 x[4] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 0.8}};
  const Tet4Geometry g = tet4_geometry(x[0], x[1], x[2], x[3]);
  Mat3 A;
  A << 1e-3, 2e-3, -1e-3, 0.5e-3, -2e-3, 3e-3, 1e-3, 1e-3, 4e-3;
  Eigen::Matrix<double, 12, 1> u;
  for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = A * x[a];
  const auto e = tet4_strain(g, u);
  EXPECT_NEAR(e[0], A(0, 0), 1e-15);
  EXPECT_NEAR(e[1], A(1, 1), 1e-15);
  EXPECT_NEAR(e[2], A(2, 2), 1e-15);
  EXPECT_NEAR(e[3], A(1, 2) + A(2, 1), 1e-15);
  EXPECT_NEAR(e[4], A(0, 2) + A(2, 0), 1e-15);
  EXPECT_NEAR(e[5], A(0, 1) + A(1, 0), 1e-15);
}

TEST(Tet4Element, StrainEnergyMatchesTheContinuumFormula) {
  // For a constant strain, u^T K u / 2 = V (lambda tr(e)^2 / 2 + mu e:e): an independent formula.
  const Vec3 x[4] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 0.8}};
  const Tet4Geometry g = tet4_geometry(x[0], x[1], x[2], x[3]);
  Mat3 A;
  A << 1e-3, 2e-3, -1e-3, 0.5e-3, -2e-3, 3e-3, 1e-3, 1e-3, 4e-3;
  Eigen::Matrix<double, 12, 1> u;
  for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = A * x[a];
  const Mat3 eps = 0.5 * (A + A.transpose());
  const double expected = g.volume * (0.5 * rubber.lambda * eps.trace() * eps.trace() + rubber.mu * eps.squaredNorm());
  EXPECT_NEAR(0.5 * u.dot(tet4_stiffness(g, rubber) * u), expected, 1e-12 * expected);
}

}  // namespace
}  // namespace roifem::fem
