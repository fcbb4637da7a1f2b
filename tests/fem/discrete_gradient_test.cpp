// SPDX-License-Identifier: GPL-3.0-or-later
// Gonzalez's discrete gradient of the neo-Hookean law (fem/discrete_gradient.hpp) and its element
// and assembled forces, each against an independent expectation: the second Piola-Kirchhoff
// stress of the strain against F^-1 P of the displacement gradient (and the linear law at a strain
// of 1e-9); the directionality identity S_alg : dE = W(b) - W(a) and its element and assembled
// forms f . (u_b - u_a) = E(u_b) - E(u_a); consistency with the force at the mean state, to second
// order; zero net force and zero torque about the mean configuration (angular momentum); the
// material tangent dS/dE and the discrete gradient's derivative in the second state, pointwise, per
// element and assembled, against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fem/discrete_gradient.hpp"
#include "fem/dof_map.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "fem/hyperelastic_element.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/tet10.hpp"
#include "fem/tet4.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/quadratic_mesh.hpp"

namespace roifem::fem {
namespace {

const Material discrete_gradient_tissue = [] {
  Material m = Material::from_young_poisson(3000, 0.45, 1000, 0);
  m.model = MaterialModel::neo_hookean;
  return m;
}();
const NeoHookean dg_law = NeoHookean::of(discrete_gradient_tissue);

Mat3 gradient_within(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> draw(-amplitude, amplitude);
  Mat3 H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = draw(rng);
  return H;
}

TEST(DiscreteGradient, StressOfTheStrainIsTheSecondPiolaKirchhoffStress) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Mat3 H = gradient_within(rng, 0.35);
    const Mat3 F = Mat3::Identity() + H;
    ASSERT_GT(F.determinant(), 0.2);
    const Mat3 S_expected = F.inverse() * dg_law.stress(H);
    const Mat3 S = dg_law.stress_of_strain(green_lagrange(H));
    EXPECT_LT((S - S_expected).norm(), 1e-12 * S_expected.norm()) << "trial " << trial;
  }
  // At a strain of 1e-9 it keeps its digits: the linear law's lambda tr(E) I + 2 mu E to 1e-8.
  const Mat3 E = 1e-9 * green_lagrange(gradient_within(rng, 1.0));
  const Mat3 S = dg_law.stress_of_strain(0.5 * (E + E.transpose()));
  const Mat3 linear = discrete_gradient_tissue.lambda * E.trace() * Mat3::Identity() + 2 * discrete_gradient_tissue.mu * E;
  EXPECT_LT((S - linear).norm(), 1e-8 * linear.norm());
}

TEST(DiscreteGradient, ItsWorkOnTheStrainIncrementIsTheEnergyIncrement) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    // Steps from large (0.3) to small (1e-6), where the correction is a near-cancellation.
    const double step = 0.3 * std::pow(10.0, -trial / 4);
    const Mat3 H_a = gradient_within(rng, 0.3), H_b = H_a + gradient_within(rng, step);
    const Mat3 dE = green_lagrange(H_b) - green_lagrange(H_a);
    const double dW = dg_law.energy(H_b) - dg_law.energy(H_a);
    const double work = discrete_gradient_stress(dg_law, H_a, H_b).cwiseProduct(dE).sum();
    EXPECT_NEAR(work, dW, 1e-12 * (dg_law.energy(H_a) + dg_law.energy(H_b))) << "trial " << trial << ", step " << step;
  }
}

TEST(DiscreteGradient, ConvergesToTheStressAtTheMeanStrainAtSecondOrder) {
  std::mt19937 rng(5);
  const Mat3 H = gradient_within(rng, 0.3), D = gradient_within(rng, 1.0);
  // S_alg(H - h D/2, H + h D/2) - S(E(H)): the midpoint's strain differs from E(H) by O(h^2), and
  // so does the correction.
  double previous = 0;
  for (const double h : {1e-2, 5e-3, 2.5e-3}) {
    const Mat3 S_alg = discrete_gradient_stress(dg_law, H - 0.5 * h * D, H + 0.5 * h * D);
    const double error = (S_alg - dg_law.stress_of_strain(green_lagrange(H))).norm();
    if (previous > 0) {
      EXPECT_NEAR(previous / error, 4.0, 0.2) << "h = " << h;
    }
    previous = error;
  }
  // Between a state and itself it is the stress (to rounding: the volumetric part has its own formula).
  const Mat3 S = dg_law.stress_of_strain(green_lagrange(H));
  EXPECT_LT((discrete_gradient_stress(dg_law, H, H) - S).norm(), 1e-14 * S.norm());
}

/// A distorted tetrahedron and two random nodal states on it.
struct TwoStates {
  Vec3 x[4] = {Vec3(0, 0, 0), Vec3(1.1, 0.1, -0.1), Vec3(0.2, 0.9, 0.1), Vec3(-0.1, 0.2, 1.2)};
  Eigen::Matrix<double, 12, 1> u_a, u_b;
  explicit TwoStates(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> draw(-0.15, 0.15);
    for (int i = 0; i < 12; ++i) u_a[i] = draw(rng);
    for (int i = 0; i < 12; ++i) u_b[i] = u_a[i] + draw(rng);
  }
};

TEST(DiscreteGradient, Tet4AndTet10ForcesDoTheEnergysIncrementAndNoNetForceOrTorque) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const TwoStates t(seed);
    const Tet4Geometry g = tet4_geometry(t.x[0], t.x[1], t.x[2], t.x[3]);
    const auto r = tet4_discrete_gradient(g, dg_law, t.u_a, t.u_b);
    ASSERT_GT(r.min_J, 0);
    const double E_a = tet4_hyperelastic(g, dg_law, t.u_a, Evaluate::energy).energy;
    const double E_b = tet4_hyperelastic(g, dg_law, t.u_b, Evaluate::energy).energy;
    EXPECT_NEAR(r.force.dot(t.u_b - t.u_a), E_b - E_a, 1e-12 * (E_a + E_b)) << "seed " << seed;
    EXPECT_NEAR(r.energy, E_b, 1e-15 * E_b);
    // Linear and angular momentum: sum f_a = 0 and sum x_mid,a x f_a = 0 (F_mid S F_mid^T symmetric).
    Vec3 net = Vec3::Zero(), torque = Vec3::Zero();
    for (int a = 0; a < 4; ++a) {
      const Vec3 f = r.force.segment<3>(3 * a);
      const Vec3 x_mid = t.x[a] + 0.5 * (t.u_a.segment<3>(3 * a) + t.u_b.segment<3>(3 * a));
      net += f;
      torque += x_mid.cross(f);
    }
    EXPECT_LT(net.norm(), 1e-12 * r.force.norm());
    EXPECT_LT(torque.norm(), 1e-12 * r.force.norm());

    // tet10: midside nodes displaced off the edges' means, so the gradient varies over the element.
    const Tet10Geometry g10 = tet10_geometry(t.x[0], t.x[1], t.x[2], t.x[3]);
    Eigen::Matrix<double, 30, 1> u10_a, u10_b;
    for (int a = 0; a < 4; ++a) {
      u10_a.segment<3>(3 * a) = t.u_a.segment<3>(3 * a);
      u10_b.segment<3>(3 * a) = t.u_b.segment<3>(3 * a);
    }
    for (int k = 0; k < 6; ++k) {
      const auto& e = tet10_edges[static_cast<std::size_t>(k)];
      const Vec3 bulge(0.01 * k, -0.005 * k, 0.02);
      u10_a.segment<3>(3 * (4 + k)) = 0.5 * (t.u_a.segment<3>(3 * e[0]) + t.u_a.segment<3>(3 * e[1])) + bulge;
      u10_b.segment<3>(3 * (4 + k)) = 0.5 * (t.u_b.segment<3>(3 * e[0]) + t.u_b.segment<3>(3 * e[1])) - bulge;
    }
    const auto r10 = tet10_discrete_gradient(g10, dg_law, u10_a, u10_b);
    ASSERT_GT(r10.min_J, 0);
    const double E10_a = tet10_hyperelastic(g10, dg_law, u10_a, Evaluate::energy).energy;
    const double E10_b = tet10_hyperelastic(g10, dg_law, u10_b, Evaluate::energy).energy;
    EXPECT_NEAR(r10.force.dot(u10_b - u10_a), E10_b - E10_a, 1e-12 * (E10_a + E10_b)) << "seed " << seed;
  }
}

TEST(DiscreteGradient, StrainTangentIsTheDerivativeOfTheStress) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 E = green_lagrange(gradient_within(rng, 0.3));
    Mat3 dE = gradient_within(rng, 1.0);
    dE = 0.5 * (dE + dE.transpose());
    const double h = 1e-6;
    const Mat3 fd = (dg_law.stress_of_strain(E + h * dE) - dg_law.stress_of_strain(E - h * dE)) / (2 * h);
    const Mat9 D = dg_law.strain_tangent(E);
    const Eigen::Matrix<double, 9, 1> dS = D * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dE.data());
    const Mat3 analytic = Eigen::Map<const Mat3>(dS.data());
    EXPECT_LT((analytic - fd).norm(), 1e-7 * fd.norm()) << "trial " << trial;
    EXPECT_LT((D - D.transpose()).norm(), 1e-12 * D.norm()) << "hyperelastic: major symmetry";
  }
}

/// max |D vec(dE_b) - central difference of S_alg in H_b| / |difference|, for H_b - H_a of `step`.
double discrete_gradient_tangent_error(std::mt19937& rng, double step) {
  const Mat3 H_a = gradient_within(rng, 0.3), H_b = H_a + gradient_within(rng, step);
  const Mat3 dH = gradient_within(rng, 1.0);
  const double h = 1e-4 * step;  // S_alg varies on the scale of dE; its rounding grows as 1/(h dE)
  Mat9 D;
  discrete_gradient_stress(dg_law, H_a, H_b, D);
  const Mat3 fd =
      (discrete_gradient_stress(dg_law, H_a, H_b + h * dH) - discrete_gradient_stress(dg_law, H_a, H_b - h * dH)) / (2 * h);
  const Mat3 F_b = Mat3::Identity() + H_b;
  const Mat3 dE_b = 0.5 * (F_b.transpose() * dH + dH.transpose() * F_b);
  const Eigen::Matrix<double, 9, 1> dS = D * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dE_b.data());
  return (Eigen::Map<const Mat3>(dS.data()) - fd).norm() / fd.norm();
}

TEST(DiscreteGradient, ItsTangentIsTheDerivativeInTheSecondState) {
  std::mt19937 rng(23);
  // Steps on both sides of large_increment: the energies' difference and the quadrature.
  for (const double step : {0.3, 0.05, 3e-3, 5e-4, 1e-5}) {
    for (int trial = 0; trial < 3; ++trial) {
      const double error = discrete_gradient_tangent_error(rng, step);
      EXPECT_LT(error, 1e-6) << "step " << step << ", trial " << trial;
    }
  }
}

TEST(DiscreteGradient, Tet4AndTet10TangentsAreTheForcesDerivativesInTheSecondState) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const TwoStates t(seed);
    const Tet4Geometry g = tet4_geometry(t.x[0], t.x[1], t.x[2], t.x[3]);
    const auto r = tet4_discrete_gradient(g, dg_law, t.u_a, t.u_b, Evaluate::force_and_tangent);
    ASSERT_GT(r.min_J, 0);
    const double h = 1e-7;
    Eigen::Matrix<double, 12, 12> fd;
    for (int j = 0; j < 12; ++j) {
      Eigen::Matrix<double, 12, 1> plus = t.u_b, minus = t.u_b;
      plus[j] += h;
      minus[j] -= h;
      fd.col(j) = (tet4_discrete_gradient(g, dg_law, t.u_a, plus).force - tet4_discrete_gradient(g, dg_law, t.u_a, minus).force) /
                  (2 * h);
    }
    EXPECT_LT((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "seed " << seed;
    EXPECT_GT((r.tangent - r.tangent.transpose()).norm(), 1e-4 * fd.norm()) << "not symmetric: the test sees the difference";
    // At u_a = u_b it is half the tangent: d f_alg(u, u + d) / dd at d = 0.
    const auto same = tet4_discrete_gradient(g, dg_law, t.u_a, t.u_a, Evaluate::force_and_tangent);
    const auto K = tet4_hyperelastic(g, dg_law, t.u_a, Evaluate::force_and_tangent).tangent;
    EXPECT_LT((2 * same.tangent - K).norm(), 1e-12 * K.norm());

    const Tet10Geometry g10 = tet10_geometry(t.x[0], t.x[1], t.x[2], t.x[3]);
    Eigen::Matrix<double, 30, 1> u10_a = Eigen::Matrix<double, 30, 1>::Zero(), u10_b;
    u10_a.head<12>() = t.u_a;
    for (int k = 0; k < 6; ++k) {
      const auto& e = tet10_edges[static_cast<std::size_t>(k)];
      u10_a.segment<3>(3 * (4 + k)) = 0.5 * (t.u_a.segment<3>(3 * e[0]) + t.u_a.segment<3>(3 * e[1])) + Vec3(0.01 * k, 0, 0.02);
    }
    u10_b = u10_a;
    u10_b.head<12>() = t.u_b;
    const auto r10 = tet10_discrete_gradient(g10, dg_law, u10_a, u10_b, Evaluate::force_and_tangent);
    ASSERT_GT(r10.min_J, 0);
    Eigen::Matrix<double, 30, 30> fd10;
    for (int j = 0; j < 30; ++j) {
      Eigen::Matrix<double, 30, 1> plus = u10_b, minus = u10_b;
      plus[j] += h;
      minus[j] -= h;
      fd10.col(j) =
          (tet10_discrete_gradient(g10, dg_law, u10_a, plus).force - tet10_discrete_gradient(g10, dg_law, u10_a, minus).force) /
          (2 * h);
    }
    EXPECT_LT((r10.tangent - fd10).norm(), 1e-6 * fd10.norm()) << "seed " << seed;
  }
}

TEST(DiscreteGradient, AssembledForceDoesTheEnergysIncrementAndIsTheForceAtOneState) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  Constraints constraints(mesh.num_nodes());
  for (const int n : mesh.sets.at("x0").nodes) constraints.fix_node(n, Vec3::Zero());
  const DofMap dofs(constraints);
  const MaterialMap materials(discrete_gradient_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> draw(-2e-3, 2e-3);
  Vector u_a(dofs.num_free()), u_b(dofs.num_free());
  for (Index i = 0; i < u_a.size(); ++i) u_a[i] = draw(rng);
  for (Index i = 0; i < u_b.size(); ++i) u_b[i] = u_a[i] + draw(rng);
  const Vector full_a = dofs.expand(u_a), full_b = dofs.expand(u_b);
  Vector f_alg(dofs.num_free()), f(dofs.num_free());
  assembler.discrete_gradient(full_a, full_b, f_alg);
  const double W_a = assembler.energy(full_a), W_b = assembler.energy(full_b);
  EXPECT_NEAR(f_alg.dot(u_b - u_a), W_b - W_a, 1e-12 * (W_a + W_b));
  assembler.discrete_gradient(full_a, full_a, f_alg);
  assembler.force(full_a, f);
  EXPECT_LT((f_alg - f).norm(), 1e-13 * f.norm());
  // The assembled df_alg/du_b, against a directional difference.
  SparseMatrix K_alg;
  assembler.discrete_gradient_and_tangent(full_a, full_b, f_alg, K_alg);
  Vector direction(dofs.num_free()), plus(dofs.num_free()), minus(dofs.num_free());
  for (Index i = 0; i < direction.size(); ++i) direction[i] = draw(rng);
  const double h = 1e-4;
  assembler.discrete_gradient(full_a, dofs.expand(u_b + h * direction), plus);
  assembler.discrete_gradient(full_a, dofs.expand(u_b - h * direction), minus);
  const Vector fd = (plus - minus) / (2 * h);
  EXPECT_LT((K_alg * direction - fd).norm(), 1e-6 * fd.norm());
}

}  // namespace
}  // namespace roifem::fem
