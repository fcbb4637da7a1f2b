// SPDX-License-Identifier: GPL-3.0-or-later
// The neo-Hookean law and elements (fem/neo_hookean.hpp, fem/hyperelastic_element.hpp,
// fem/hyperelastic_assembly.hpp, fem/hyperelastic_static.hpp), each against an independent
// expectation: the stress and tangent against finite differences of the energy and the stress;
// the tangent at F = I against the linear law; the stress and energy at a strain of 1e-9 against it; the stress against the
// spatial (Cauchy) form of the same law; homogeneous large deformations (a stretch of 1.5, a shear) reproduced exactly inside a
// distorted mesh; a rigid rotation by 90 degrees free of force (the linear element is not); the
// linear answer recovered at small load; an inverted element named.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "fem/hyperelastic_element.hpp"
#include "fem/hyperelastic_static.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/static_solve.hpp"
#include "fem/tet4_excess_batch.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "test_support.hpp"

namespace roifem::fem {
namespace {

const Material neo_hookean_tissue = [] {
  Material m = Material::from_young_poisson(3000, 0.45, 1000, 0);
  m.model = MaterialModel::neo_hookean;
  return m;
}();
const NeoHookean tissue_law = NeoHookean::of(neo_hookean_tissue);

/// A displacement gradient H = F - I with entries up to `amplitude`.
Mat3 random_gradient(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> draw(-amplitude, amplitude);
  Mat3 H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = draw(rng);
  return H;
}

TEST(NeoHookean, StressIsTheEnergysDerivativeAndTheTangentTheStresss) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 F = random_gradient(rng, 0.3);  // here: H, perturbed entry by entry as F would be
    ASSERT_GT((Mat3::Identity() + F).determinant(), 0.2);
    Mat3 P;
    Mat9 A;
    tissue_law.stress_and_tangent(F, P, A);
    EXPECT_LT((P - tissue_law.stress(F)).norm(), 1e-12 * P.norm());
    EXPECT_NEAR(NeoHookean::J_minus_1(F), (Mat3::Identity() + F).determinant() - 1, 1e-15);
    const double h = 1e-6;
    Mat3 P_fd;
    Mat9 A_fd;
    for (int k = 0; k < 3; ++k)
      for (int L = 0; L < 3; ++L) {
        Mat3 Fp = F, Fm = F;
        Fp(k, L) += h;
        Fm(k, L) -= h;
        P_fd(k, L) = (tissue_law.energy(Fp) - tissue_law.energy(Fm)) / (2 * h);
        const Mat3 dP = (tissue_law.stress(Fp) - tissue_law.stress(Fm)) / (2 * h);
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J) A_fd(3 * i + J, 3 * k + L) = dP(i, J);
      }
    EXPECT_LT((P - P_fd).norm() / P.norm(), 1e-6) << trial;
    EXPECT_LT((A - A_fd).norm() / A.norm(), 1e-6) << trial;
    EXPECT_LT((A - A.transpose()).norm() / A.norm(), 1e-13) << "a hyperelastic tangent is symmetric";
  }
}

TEST(NeoHookean, TangentAtRestIsTheLinearLawWithTheSameLameConstants) {
  Mat3 P;
  Mat9 A;
  tissue_law.stress_and_tangent(Mat3::Zero(), P, A);
  EXPECT_EQ(P.norm(), 0.0);
  EXPECT_EQ(tissue_law.energy(Mat3::Zero()), 0.0);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const double linear = neo_hookean_tissue.lambda * (i == J) * (k == L) +
                                neo_hookean_tissue.mu * ((i == k) * (J == L) + (i == L) * (J == k));
          EXPECT_NEAR(A(3 * i + J, 3 * k + L), linear, 1e-12 * neo_hookean_tissue.lambda) << i << J << k << L;
        }
}

TEST(NeoHookean, FirstPiolaStressEqualsTheSpatialFormOfTheLaw) {
  // sigma = mu / J (bbar - tr(bbar)/3 I) + kappa (J - 1) I with bbar = J^(-2/3) F F^T, and P = J sigma F^-T.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 H = random_gradient(rng, 0.4);
    const Mat3 F = Mat3::Identity() + H;
    const double J = F.determinant();
    const Mat3 bbar = std::pow(J, -2.0 / 3.0) * F * F.transpose();
    const Mat3 sigma =
        tissue_law.mu() / J * (bbar - bbar.trace() / 3 * Mat3::Identity()) + tissue_law.kappa() * (J - 1) * Mat3::Identity();
    const Mat3 P = J * sigma * F.inverse().transpose();
    EXPECT_LT((tissue_law.stress(H) - P).norm() / P.norm(), 1e-13);
    // W in the textbook form, at a strain where it loses nothing.
    const double W = tissue_law.C10 * (std::pow(J, -2.0 / 3.0) * F.squaredNorm() - 3) + (J - 1) * (J - 1) / tissue_law.D1;
    EXPECT_NEAR(tissue_law.energy(H) / W, 1.0, 1e-13);
  }
  EXPECT_DOUBLE_EQ(tissue_law.kappa(), neo_hookean_tissue.lambda + 2 * neo_hookean_tissue.mu / 3);
}

TEST(NeoHookean, KeepsItsDigitsAtTinyStrainWhereItIsTheLinearLaw) {
  // At a strain of 1e-9 P and W are the linear law's to O(1e-9); the textbook form
  // F - I1/3 F^-T would lose half its digits to cancellation there.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> draw(-1, 1);
  Mat3 H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = 1e-9 * draw(rng);
  const Mat3 eps = 0.5 * (H + H.transpose());
  const Mat3 sigma = neo_hookean_tissue.lambda * eps.trace() * Mat3::Identity() + 2 * neo_hookean_tissue.mu * eps;
  const double W = 0.5 * (sigma.array() * eps.array()).sum();
  EXPECT_LT((tissue_law.stress(H) - sigma).norm() / sigma.norm(), 1e-7);
  EXPECT_NEAR(tissue_law.energy(H) / W, 1.0, 1e-7);
  Mat3 P;
  Mat9 A;
  tissue_law.stress_and_tangent(H, P, A);
  EXPECT_LT((P - sigma).norm() / sigma.norm(), 1e-7);
}

/// A skewed tetrahedron, positively oriented.
std::array<Vec3, 4> skewed_tetrahedron() {
  return {Vec3(0, 0, 0), Vec3(1.2, 0.1, -0.1), Vec3(0.3, 0.9, 0.2), Vec3(0.2, 0.3, 1.1)};
}

template <int N, class Evaluate>
void expect_consistent(const Eigen::Matrix<double, 3 * N, 1>& ue, Evaluate evaluate) {
  const auto r = evaluate(ue, fem::Evaluate::force_and_tangent);
  ASSERT_GT(r.min_J, 0);
  const double h = 1e-7;
  Eigen::Matrix<double, 3 * N, 1> f_fd;
  Eigen::Matrix<double, 3 * N, 3 * N> K_fd;
  for (int j = 0; j < 3 * N; ++j) {
    auto up = ue, um = ue;
    up[j] += h;
    um[j] -= h;
    const auto rp = evaluate(up, fem::Evaluate::energy), rm = evaluate(um, fem::Evaluate::energy);
    f_fd[j] = (rp.energy - rm.energy) / (2 * h);
    K_fd.col(j) = (rp.force - rm.force) / (2 * h);
  }
  EXPECT_LT((r.force - f_fd).norm() / r.force.norm(), 1e-6);
  EXPECT_LT((r.tangent - K_fd).norm() / r.tangent.norm(), 1e-6);
  std::printf("%d-node element: |f - dE/du| / |f| = %.2e, |K - df/du| / |K| = %.2e\n", N,
              (r.force - f_fd).norm() / r.force.norm(), (r.tangent - K_fd).norm() / r.tangent.norm());
}

TEST(HyperelasticElement, Tet4ForceAndTangentMatchFiniteDifferences) {
  const auto x = skewed_tetrahedron();
  const Tet4Geometry g = tet4_geometry(x[0], x[1], x[2], x[3]);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> draw(-0.15, 0.15);
  Eigen::Matrix<double, 12, 1> ue;
  for (int i = 0; i < 12; ++i) ue[i] = draw(rng);
  expect_consistent<4>(ue, [&](const auto& u, Evaluate what) { return tet4_hyperelastic(g, tissue_law, u, what); });
}

TEST(HyperelasticElement, Tet10ForceAndTangentMatchFiniteDifferences) {
  const auto x = skewed_tetrahedron();
  const Tet10Geometry g = tet10_geometry(x[0], x[1], x[2], x[3]);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> draw(-0.08, 0.08);
  Eigen::Matrix<double, 30, 1> ue;
  for (int i = 0; i < 30; ++i) ue[i] = draw(rng);
  expect_consistent<10>(ue, [&](const auto& u, Evaluate what) { return tet10_hyperelastic(g, tissue_law, u, what); });
}

TEST(HyperelasticElement, SmallDisplacementGivesTheLinearElementsForceAndStiffness) {
  const auto x = skewed_tetrahedron();
  const Tet4Geometry g = tet4_geometry(x[0], x[1], x[2], x[3]);
  const ElementMatrix K = tet4_stiffness(g, neo_hookean_tissue);
  const auto at_rest = tet4_hyperelastic(g, tissue_law, Eigen::Matrix<double, 12, 1>::Zero(), Evaluate::force_and_tangent);
  EXPECT_LT((at_rest.tangent - K).norm() / K.norm(), 1e-13);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> draw(-1, 1);
  Eigen::Matrix<double, 12, 1> ue;
  for (int i = 0; i < 12; ++i) ue[i] = 1e-7 * draw(rng);
  const auto r = tet4_hyperelastic(g, tissue_law, ue, Evaluate::force);
  EXPECT_LT((r.force - K * ue).norm() / (K * ue).norm(), 1e-5);  // the difference is O(|u|)
}

TEST(HyperelasticElement, RigidRotationBy90DegreesGivesNoForceWhereTheLinearElementsIsLarge) {
  const auto x = skewed_tetrahedron();
  const Tet4Geometry g4 = tet4_geometry(x[0], x[1], x[2], x[3]);
  const Tet10Geometry g10 = tet10_geometry(x[0], x[1], x[2], x[3]);
  const Mat3 R = Eigen::AngleAxisd(M_PI / 2, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix<double, 12, 1> u4;
  for (int a = 0; a < 4; ++a) u4.segment<3>(3 * a) = (R - Mat3::Identity()) * x[a];
  const auto r4 = tet4_hyperelastic(g4, tissue_law, u4, Evaluate::energy);
  // The scale: the force of a 10% stretch of the same element.
  Eigen::Matrix<double, 12, 1> stretch;
  for (int a = 0; a < 4; ++a) stretch.segment<3>(3 * a) = Vec3(0.1 * x[a].x(), 0, 0);
  const double scale = tet4_hyperelastic(g4, tissue_law, stretch, Evaluate::force).force.norm();
  EXPECT_LT(r4.force.norm(), 1e-12 * scale);
  EXPECT_NEAR(r4.energy, 0, 1e-12 * scale);
  const double linear = (tet4_stiffness(g4, neo_hookean_tissue) * u4).norm();
  EXPECT_GT(linear, 5 * scale) << "the linear element resists a rotation";
  std::printf("rotation by 90 degrees: neo-Hookean |f| = %.2e, linear |K u| = %.2e (10%% stretch: %.2e)\n", r4.force.norm(),
              linear, scale);
  // tet10: its midpoints rotate with the corners.
  Eigen::Matrix<double, 30, 1> u10;
  for (int a = 0; a < 4; ++a) u10.segment<3>(3 * a) = u4.segment<3>(3 * a);
  for (int k = 0; k < 6; ++k)
    u10.segment<3>(3 * (4 + k)) = 0.5 * (u4.segment<3>(3 * tet10_edges[k][0]) + u4.segment<3>(3 * tet10_edges[k][1]));
  EXPECT_LT(tet10_hyperelastic(g10, tissue_law, u10, Evaluate::force).force.norm(), 1e-12 * scale);
}

TEST(HyperelasticElement, TheExcessIsTheForceLessTheLinearElementsAndVanishesQuadratically) {
  // Evaluate::excess forms f - K_lin u_e from the stresses, without K_lin: against the linear
  // elements' own matrices (tet4_stiffness, tet10_stiffness) at a large and at small displacements.
  const auto x = skewed_tetrahedron();
  const Tet4Geometry g4 = tet4_geometry(x[0], x[1], x[2], x[3]);
  const Tet10Geometry g10 = tet10_geometry(x[0], x[1], x[2], x[3]);
  const ElementMatrix K4 = tet4_stiffness(g4, neo_hookean_tissue);
  const auto K10 = tet10_stiffness(g10, neo_hookean_tissue);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> draw(-1, 1);
  Eigen::Matrix<double, 12, 1> u4;
  Eigen::Matrix<double, 30, 1> u10;
  for (int i = 0; i < 12; ++i) u4[i] = draw(rng);
  for (int i = 0; i < 30; ++i) u10[i] = draw(rng);
  std::vector<double> small;
  for (const double size : {0.1, 1e-2, 1e-3}) {
    const Eigen::Matrix<double, 12, 1> a4 = size * u4;
    const Eigen::Matrix<double, 30, 1> a10 = 0.5 * size * u10;
    const auto f4 = tet4_hyperelastic(g4, tissue_law, a4, Evaluate::force);
    const auto e4 = tet4_hyperelastic(g4, tissue_law, a4, Evaluate::excess);
    const auto f10 = tet10_hyperelastic(g10, tissue_law, a10, Evaluate::force);
    const auto e10 = tet10_hyperelastic(g10, tissue_law, a10, Evaluate::excess);
    EXPECT_LT((e4.force - (f4.force - K4 * a4)).norm(), 1e-13 * (K4 * a4).norm()) << size;
    EXPECT_LT((e10.force - (f10.force - K10 * a10)).norm(), 1e-13 * (K10 * a10).norm()) << size;
    small.push_back(e4.force.norm() / (K4 * a4).norm());
  }
  // O(|u|^2): the excess relative to the linear force falls by the displacement's factor.
  EXPECT_NEAR(small[1] / small[0], 0.1, 0.02);
  EXPECT_NEAR(small[2] / small[1], 0.1, 0.01);
}

TEST(HyperelasticElement, TheEightLaneExcessKernelIsTheElementByElementOneFromTinyToLargeStrain) {
  // tet4_excess_force_batch (the haptic tick's kernel: eight elements at once, J^(1/3) by Halley's
  // iteration) against tet4_excess_force (std::cbrt, Eigen's 3x3 algebra), lane by lane, on
  // distorted elements of different materials, from a strain of 1e-6 to J = 0.1 and J = 6 (out of
  // the iteration's range [1/4, 4]: std::cbrt there too), and a lane with no element.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> draw(-1, 1), stiffness(0.5, 2);
  double worst = 0, smallest_J = 10, largest_J = 0;
  for (const double size : {1e-6, 1e-3, 0.05, 0.15}) {
    for (int round = 0; round < 20; ++round) {
      Tet4ExcessBatch batch;
      double u[12][kTet4Lanes] = {}, excess[12][kTet4Lanes], J[kTet4Lanes];
      std::vector<Tet4Geometry> geometry;
      std::vector<NeoHookean> laws;
      std::vector<Eigen::Matrix<double, 12, 1>> displacement;
      for (int l = 0; l < kTet4Lanes - 1; ++l) {  // the last lane stays empty
        auto x = skewed_tetrahedron();
        for (Vec3& p : x) p += 0.2 * Vec3(draw(rng), draw(rng), draw(rng));
        geometry.push_back(tet4_geometry(x[0], x[1], x[2], x[3]));
        Material m = neo_hookean_tissue;
        m.mu *= stiffness(rng);
        m.lambda *= stiffness(rng);
        laws.push_back(NeoHookean::of(m));
        Eigen::Matrix<double, 12, 1> ue;
        for (int k = 0; k < 12; ++k) ue[k] = size * draw(rng);
        if (round % 5 == 0)  // a uniform stretch or compression: J far from 1
          for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) += (round % 10 == 0 ? 0.8 : -0.55) * x[static_cast<std::size_t>(a)];
        displacement.push_back(ue);
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) batch.grad[a][i][l] = geometry.back().grad(a, i);
        batch.volume[l] = std::abs(geometry.back().volume);
        batch.mu[l] = m.mu;
        batch.kappa[l] = laws.back().kappa();
        batch.lambda[l] = laws.back().kappa() - 2.0 / 3.0 * m.mu;
        for (int k = 0; k < 12; ++k) u[k][l] = ue[k];
      }
      tet4_excess_force_batch(batch, u, excess, J);
      for (int l = 0; l < kTet4Lanes - 1; ++l) {
        Eigen::Matrix<double, 12, 1> expected, lane;
        const double J_expected = tet4_excess_force(geometry[static_cast<std::size_t>(l)], laws[static_cast<std::size_t>(l)],
                                                    displacement[static_cast<std::size_t>(l)], expected);
        ASSERT_GT(J_expected, 0) << "an element drawn inverted: the draw needs changing";
        for (int k = 0; k < 12; ++k) lane[k] = excess[k][l];
        EXPECT_NEAR(J[l], J_expected, 1e-14 * J_expected);
        // The scale: the linear element's force at the same displacement.
        Material m = neo_hookean_tissue;
        m.mu = 2 * laws[static_cast<std::size_t>(l)].C10;
        m.lambda = laws[static_cast<std::size_t>(l)].kappa() - 2.0 / 3.0 * m.mu;
        const double scale =
            (tet4_stiffness(geometry[static_cast<std::size_t>(l)], m) * displacement[static_cast<std::size_t>(l)]).norm();
        worst = std::max(worst, (lane - expected).norm() / scale);
        smallest_J = std::min(smallest_J, J[l]);
        largest_J = std::max(largest_J, J[l]);
      }
      EXPECT_EQ(J[kTet4Lanes - 1], 1.0);
      for (int k = 0; k < 12; ++k) EXPECT_EQ(excess[k][kTet4Lanes - 1], 0.0);
    }
  }
  std::printf("eight-lane kernel against the element's: %.1e of the linear force; J from %.3f to %.2f\n", worst, smallest_J,
              largest_J);
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(smallest_J, 0.25);
  EXPECT_GT(largest_J, 4.0);
}

/// The distorted box (tests/test_support.hpp), linear or with midside nodes.
mesh::TetMesh distorted_box(bool quadratic) {
  const mesh::TetMesh linear = test::distorted_box(0.25, 42);
  return quadratic ? mesh::with_midside_nodes(linear) : linear;
}

/// The affine map u = (F - I) X on the boundary, solved inside: returns max |u - (F - I) X| / |F - I|
/// over the nodes and the largest |P_element - P(F)| / |P(F)| of the quadrature points (tet4: 1).
std::pair<double, int> homogeneous_error(const mesh::TetMesh& mesh, const Mat3& F) {
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh::boundary_nodes(mesh)) constraints.fix_node(n, (F - Mat3::Identity()) * mesh.node(n));
  const DofMap dofs(constraints);
  const MaterialMap materials(neo_hookean_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  const auto solution = solve_hyperelastic_static(assembler, dofs, Vector::Zero(dofs.num_free()), {1.0});
  const Vector u = dofs.prescribed() + dofs.expand_homogeneous(solution.back().u_free);
  double worst = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    worst = std::max(worst, (u.segment<3>(3 * n) - (F - Mat3::Identity()) * mesh.node(n)).norm());
  int increments = 0;
  for (const auto& r : solution.back().newton) increments += r.iterations() > 0;
  return {worst / (F - Mat3::Identity()).norm(), increments};
}

TEST(HyperelasticStatic, StretchOfOneAndAHalfAndShearAreReproducedExactlyInside) {
  Mat3 stretch = Mat3::Identity();
  stretch(0, 0) = 1.5;
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.5;
  for (const bool quadratic : {false, true}) {
    const mesh::TetMesh mesh = distorted_box(quadratic);
    for (const auto& [name, F] : {std::pair{"stretch 1.5", stretch}, std::pair{"shear 0.5", shear}}) {
      const auto [error, increments] = homogeneous_error(mesh, F);
      std::printf("%s, %s: max |u - (F - I) X| / |F - I| = %.2e (%d load increments)\n", quadratic ? "tet10" : "tet4", name,
                  error, increments);
      EXPECT_LT(error, 1e-10) << name << (quadratic ? " tet10" : " tet4");
    }
  }
}

TEST(HyperelasticStatic, SmallLoadRecoversTheLinearAnswer) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(1.0, 0.3, 0.3, 0.1);
  Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "x0");
  const DofMap dofs(constraints);
  // A tip load on the x1 face, downwards: a cantilever.
  Vector f = Vector::Zero(dofs.num_free());
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (mesh.node(n).x() > 1 - 1e-9) f[dofs.free_dof(n, 2)] = -1.0;
  const MaterialMap materials(neo_hookean_tissue);
  const Vector u_linear = solve_static(StiffnessAssembler(mesh, dofs).stiffness(materials), f, dofs);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  // Loads that give a peak displacement of 1e-3 and 1e-5 of the beam's length: the nonlinear answer
  // differs from the linear one by O(|u| / L), so relatively by about 1e-3 and 1e-5, 100x apart.
  std::vector<double> differences;
  for (const double peak : {1e-3, 1e-5}) {
    const double scale = peak / u_linear.lpNorm<Eigen::Infinity>();
    const auto u = solve_hyperelastic_static(assembler, dofs, scale * f, {1.0}).back().u_free;
    differences.push_back((u - scale * u_linear).norm() / (scale * u_linear).norm());
    std::printf("peak |u| / L = %.0e: |u_nl - u_lin| / |u_lin| = %.2e\n", peak, differences.back());
    EXPECT_LT(differences.back(), 10 * peak) << peak;
  }
  EXPECT_NEAR(differences[0] / differences[1], 100, 5) << "the difference is first order in the load";
}

TEST(HyperelasticAssembly, TangentMatchesFiniteDifferencesOfTheAssembledForce) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.5, 0.4, 0.3, 0.2);
  Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "x0");
  const DofMap dofs(constraints);
  const MaterialMap materials(neo_hookean_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> draw(-0.02, 0.02);
  Vector x(dofs.num_free());
  for (Index i = 0; i < x.size(); ++i) x[i] = draw(rng);
  Vector f(x.size()), fp(x.size()), fm(x.size());
  SparseMatrix K;
  assembler.force_and_tangent(dofs.expand(x), f, K);
  const double h = 1e-7;
  double worst = 0;
  for (Index j = 0; j < x.size(); j += 7) {
    Vector xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    assembler.force(dofs.expand(xp), fp);
    assembler.force(dofs.expand(xm), fm);
    worst = std::max(worst, (Vector(K.col(j)) - (fp - fm) / (2 * h)).norm() / Vector(K.col(j)).norm());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT((SparseMatrix(K.transpose()) - K).norm() / K.norm(), 1e-13);
}

TEST(HyperelasticAssembly, TheExcessFromTheFreeDisplacementIsTheForceLessTheLinearStiffnessProduct) {
  // excess_force_free (a haptic tick's loop: rows looked up once, the lean kernel) against the
  // assembled force less the linear K_ff u, on a box held at one end, at about 3% strain.
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.5, 0.4, 0.3, 0.2);
  Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "x0");
  const DofMap dofs(constraints);
  const MaterialMap materials(neo_hookean_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(materials);
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> draw(-0.01, 0.01);
  Vector x(dofs.num_free());
  for (Index i = 0; i < x.size(); ++i) x[i] = draw(rng);
  Vector f(x.size()), g(x.size());
  assembler.force(dofs.expand(x), f);
  assembler.excess_force_free(x, g);
  const Vector expected = f - K * x;
  EXPECT_LT((g - expected).norm(), 1e-12 * (K * x).norm());
  EXPECT_GT(g.norm(), 1e-3 * (K * x).norm()) << "a strain of a few percent: the law's excess is not negligible";
}

TEST(HyperelasticAssembly, AnInvertedElementIsNamedWithItsNodes) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(1, 1, 1, 1.0, 1.0, 1.0);
  Constraints constraints(mesh.num_nodes());
  const DofMap dofs(constraints);
  const MaterialMap materials(neo_hookean_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  Vector u = Vector::Zero(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) u[3 * n] = -2.0 * mesh.node(n).x();  // x -> -x: every element inverts
  Vector f(dofs.num_free());
  try {
    assembler.force(u, f);
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 0 (nodes"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inverted: det F = -1"), std::string::npos) << e.what();
  }
  try {  // the haptic tick's kernel (nothing held: the free displacement is u) names it the same way
    ASSERT_EQ(dofs.num_free(), u.size());
    assembler.excess_force_free(u, f);
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 0 (nodes"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inverted: det F = -1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roifem::fem
