// SPDX-License-Identifier: GPL-3.0-or-later
// The Ogden law through the law seam (fem/hyperelastic_law.hpp): its elements, its discrete
// gradient, its assembly and its static solve, each against an independent expectation: the
// element's force and tangent against central differences of its energy and force (tet4, tet10,
// one term at alpha = -20 and two terms); one term with alpha = 2 against the neo-Hookean element
// of the same moduli; the discrete gradient's work against the energy increment and its tangent
// against differences; a homogeneous compression and shear reproduced exactly inside a distorted
// mesh; the assembled excess against the force less the linear stiffness's product; a material
// with Ogden terms refused by name where its terms are outside their domain.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/discrete_gradient.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "fem/hyperelastic_element.hpp"
#include "fem/hyperelastic_law.hpp"
#include "fem/hyperelastic_static.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "test_support.hpp"

namespace roifem::fem {
namespace {

/// Brain-like moduli (mu = 1 kPa, lambda = 9 kPa) with the given Ogden terms (their mu_i sum to 1 kPa).
Material ogden_tissue(std::vector<OgdenTerm> terms) {
  Material m{.lambda = 9000, .mu = 0, .rho = 1040, .alpha = 0};
  for (const OgdenTerm& t : terms) m.mu += t.mu;
  m.model = MaterialModel::ogden;
  m.ogden = std::move(terms);
  m.validate();
  return m;
}
const Material one_term_tissue = ogden_tissue({{1000, -20}});
const Material two_term_tissue = ogden_tissue({{600, -20}, {400, 6}});

std::array<Vec3, 4> law_test_tetrahedron() {
  return {Vec3(0, 0, 0), Vec3(1.1, 0.2, -0.1), Vec3(0.2, 0.95, 0.15), Vec3(0.15, 0.25, 1.05)};
}

template <int N>
Eigen::Matrix<double, 3 * N, 1> draw_displacements(unsigned seed, double amplitude) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> draw(-amplitude, amplitude);
  Eigen::Matrix<double, 3 * N, 1> u;
  for (int i = 0; i < 3 * N; ++i) u[i] = draw(rng);
  return u;
}

/// |f - dE/du| / |f| and |K - df/du| / |K| by central differences.
template <int N, class Evaluator>
std::pair<double, double> derivative_errors(const Eigen::Matrix<double, 3 * N, 1>& ue, Evaluator evaluate) {
  const auto r = evaluate(ue, Evaluate::force_and_tangent);
  EXPECT_GT(r.min_J, 0);
  const double h = 1e-7;
  Eigen::Matrix<double, 3 * N, 1> f_fd;
  Eigen::Matrix<double, 3 * N, 3 * N> K_fd;
  for (int j = 0; j < 3 * N; ++j) {
    auto up = ue, um = ue;
    up[j] += h;
    um[j] -= h;
    const auto rp = evaluate(up, Evaluate::energy), rm = evaluate(um, Evaluate::energy);
    f_fd[j] = (rp.energy - rm.energy) / (2 * h);
    K_fd.col(j) = (rp.force - rm.force) / (2 * h);
  }
  return {(r.force - f_fd).norm() / r.force.norm(), (r.tangent - K_fd).norm() / r.tangent.norm()};
}

TEST(OgdenElement, Tet4AndTet10ForceAndTangentAreTheEnergysDerivatives) {
  const auto x = law_test_tetrahedron();
  const Tet4Geometry g4 = tet4_geometry(x[0], x[1], x[2], x[3]);
  const Tet10Geometry g10 = tet10_geometry(x[0], x[1], x[2], x[3]);
  for (const Material* m : {&one_term_tissue, &two_term_tissue}) {
    const Ogden law = Ogden::of(*m);
    const auto [f4, K4] = derivative_errors<4>(draw_displacements<4>(3, 0.1),
                                               [&](const auto& u, Evaluate what) { return tet4_hyperelastic(g4, law, u, what); });
    const auto [f10, K10] = derivative_errors<10>(
        draw_displacements<10>(4, 0.05), [&](const auto& u, Evaluate what) { return tet10_hyperelastic(g10, law, u, what); });
    std::printf("Ogden, %zu term(s): tet4 |f - dE/du| = %.1e, |K - df/du| = %.1e; tet10 %.1e, %.1e (relative)\n",
                law.terms().size(), f4, K4, f10, K10);
    EXPECT_LT(f4, 1e-6);
    EXPECT_LT(K4, 1e-6);
    EXPECT_LT(f10, 1e-6);
    EXPECT_LT(K10, 1e-6);
  }
}

TEST(OgdenElement, OneTermWithAlphaTwoIsTheNeoHookeanElement) {
  const auto x = law_test_tetrahedron();
  const Tet4Geometry g4 = tet4_geometry(x[0], x[1], x[2], x[3]);
  const Tet10Geometry g10 = tet10_geometry(x[0], x[1], x[2], x[3]);
  const Material ogden = ogden_tissue({{1000, 2}});
  Material neo_hookean = ogden;
  neo_hookean.model = MaterialModel::neo_hookean;
  neo_hookean.ogden.clear();
  const Ogden o = Ogden::of(ogden);
  const NeoHookean n = NeoHookean::of(neo_hookean);
  const auto u4 = draw_displacements<4>(8, 0.2);
  const auto u10 = draw_displacements<10>(9, 0.1);
  for (const Evaluate what : {Evaluate::energy, Evaluate::excess, Evaluate::force_and_tangent}) {
    const auto a4 = tet4_hyperelastic(g4, o, u4, what), b4 = tet4_hyperelastic(g4, n, u4, what);
    const auto a10 = tet10_hyperelastic(g10, o, u10, what), b10 = tet10_hyperelastic(g10, n, u10, what);
    EXPECT_LT((a4.force - b4.force).norm(), 1e-11 * b4.force.norm());
    EXPECT_LT((a10.force - b10.force).norm(), 1e-11 * b10.force.norm());
    if (what == Evaluate::energy) {
      EXPECT_NEAR(a4.energy, b4.energy, 1e-11 * b4.energy);
      EXPECT_NEAR(a10.energy, b10.energy, 1e-11 * b10.energy);
    }
    if (what == Evaluate::force_and_tangent) {
      EXPECT_LT((a4.tangent - b4.tangent).norm(), 1e-11 * b4.tangent.norm());
      EXPECT_LT((a10.tangent - b10.tangent).norm(), 1e-11 * b10.tangent.norm());
    }
  }
}

Mat3 law_test_gradient(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> draw(-amplitude, amplitude);
  Mat3 H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = draw(rng);
  return H;
}

TEST(OgdenDiscreteGradient, ItsWorkIsTheEnergyIncrementAndItsTangentTheDerivativeInTheSecondState) {
  std::mt19937 rng(31);
  for (const Material* m : {&one_term_tissue, &two_term_tissue}) {
    const Ogden law = Ogden::of(*m);
    double worst_work = 0, worst_tangent = 0;
    // Steps from large to below negligible_increment: the energies' difference, the quadrature, none.
    for (const double step : {0.1, 0.01, 3e-3, 5e-4, 1e-5, 1e-8}) {
      const Mat3 H_a = law_test_gradient(rng, 0.12), H_b = H_a + law_test_gradient(rng, step);
      const Mat3 dE = green_lagrange(H_b) - green_lagrange(H_a);
      const double dW = law.energy(H_b) - law.energy(H_a);
      Mat9 D;
      const Mat3 S = discrete_gradient_stress(law, H_a, H_b, D);
      worst_work = std::max(worst_work, std::abs(S.cwiseProduct(dE).sum() - dW) / (law.energy(H_a) + law.energy(H_b)));
      if (step < 1e-6) continue;  // S_alg = S(E_mid) there: its derivative is the law's, checked by OgdenTest
      const Mat3 dH = law_test_gradient(rng, 1.0);
      const double h = 1e-4 * step;
      const Mat3 fd =
          (discrete_gradient_stress(law, H_a, H_b + h * dH) - discrete_gradient_stress(law, H_a, H_b - h * dH)) / (2 * h);
      const Mat3 F_b = Mat3::Identity() + H_b;
      const Mat3 dE_b = 0.5 * (F_b.transpose() * dH + dH.transpose() * F_b);
      const Eigen::Matrix<double, 9, 1> dS = D * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dE_b.data());
      worst_tangent = std::max(worst_tangent, (Eigen::Map<const Mat3>(dS.data()) - fd).norm() / fd.norm());
    }
    std::printf("Ogden, %zu term(s): |S_alg : dE - dW| / W = %.1e, tangent %.1e (relative)\n", law.terms().size(), worst_work,
                worst_tangent);
    EXPECT_LT(worst_work, 1e-11);
    EXPECT_LT(worst_tangent, 1e-6);
  }
}

/// The distorted box (tests/test_support.hpp), linear or with midside nodes.
mesh::TetMesh jittered_box(bool quadratic) {
  const mesh::TetMesh linear = test::distorted_box(0.25, 43);
  return quadratic ? mesh::with_midside_nodes(linear) : linear;
}

TEST(OgdenAssembly, StaticCompressionAndShearAreReproducedExactlyInsideADistortedMesh) {
  Mat3 compression = Mat3::Identity();
  compression(0, 0) = 0.85;
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.3;
  for (const bool quadratic : {false, true}) {
    const mesh::TetMesh mesh = jittered_box(quadratic);
    for (const auto& [name, F] : {std::pair{"compression 0.85", compression}, std::pair{"shear 0.3", shear}}) {
      Constraints constraints(mesh.num_nodes());
      for (int n : mesh::boundary_nodes(mesh)) constraints.fix_node(n, (F - Mat3::Identity()) * mesh.node(n));
      const DofMap dofs(constraints);
      const MaterialMap materials(two_term_tissue);
      const HyperelasticAssembler assembler(mesh, dofs, materials);
      const auto solution = solve_hyperelastic_static(assembler, dofs, Vector::Zero(dofs.num_free()), {1.0});
      const Vector u = dofs.prescribed() + dofs.expand_homogeneous(solution.back().u_free);
      double worst = 0;
      for (int n = 0; n < mesh.num_nodes(); ++n)
        worst = std::max(worst, (u.segment<3>(3 * n) - (F - Mat3::Identity()) * mesh.node(n)).norm());
      worst /= (F - Mat3::Identity()).norm();
      std::printf("Ogden %s, %s: max |u - (F - I) X| / |F - I| = %.2e\n", quadratic ? "tet10" : "tet4", name, worst);
      EXPECT_LT(worst, 1e-10) << name << (quadratic ? " tet10" : " tet4");
    }
  }
}

TEST(OgdenAssembly, TheTangentAndTheExcessAreTheAssembledForcesDerivativeAndExcess) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.5, 0.4, 0.3, 0.2);
  Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "x0");
  const DofMap dofs(constraints);
  const MaterialMap materials(one_term_tissue);
  const HyperelasticAssembler assembler(mesh, dofs, materials);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> draw(-0.01, 0.01);
  Vector x(dofs.num_free());
  for (Index i = 0; i < x.size(); ++i) x[i] = draw(rng);
  Vector f(x.size()), fp(x.size()), fm(x.size()), g(x.size());
  SparseMatrix K_t;
  assembler.force_and_tangent(dofs.expand(x), f, K_t);
  const double h = 1e-7;
  double worst = 0;
  for (Index j = 0; j < x.size(); j += 5) {
    Vector xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    assembler.force(dofs.expand(xp), fp);
    assembler.force(dofs.expand(xm), fm);
    worst = std::max(worst, (Vector(K_t.col(j)) - (fp - fm) / (2 * h)).norm() / Vector(K_t.col(j)).norm());
  }
  EXPECT_LT(worst, 1e-6);
  // The excess (element by element: the eight-lane kernel is neo-Hookean's) is f - K_lin x.
  const SparseMatrix K = StiffnessAssembler(mesh, dofs).stiffness(materials);
  assembler.excess_force_free(x, g);
  EXPECT_LT((g - (f - K * x)).norm(), 1e-11 * (K * x).norm());
  EXPECT_GT(g.norm(), 1e-2 * (K * x).norm()) << "alpha = -20 at a strain of a few percent: the excess is not small";
}

TEST(OgdenMaterial, RefusesTermsOutsideTheirDomainAndTermsOfAnotherLawByName) {
  auto refusal = [](Material m) {
    try {
      m.validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Material m = one_term_tissue;
  m.ogden[0].alpha = 0;
  EXPECT_NE(refusal(m).find("term 1: alpha = 0"), std::string::npos) << refusal(m);
  m = two_term_tissue;
  m.ogden[1].mu = -5;
  EXPECT_NE(refusal(m).find("term 2: mu = -5"), std::string::npos) << refusal(m);
  m = two_term_tissue;
  m.mu = 900;
  EXPECT_NE(refusal(m).find("sum to 1000 Pa, not to the shear modulus mu = 900"), std::string::npos) << refusal(m);
  m = two_term_tissue;
  m.model = MaterialModel::neo_hookean;
  EXPECT_NE(refusal(m).find("given to the neo-hookean law"), std::string::npos) << refusal(m);
  m = one_term_tissue;
  m.ogden.clear();
  EXPECT_NE(refusal(m).find("no term"), std::string::npos) << refusal(m);
  EXPECT_EQ(refusal(two_term_tissue), "accepted");
}

}  // namespace
}  // namespace roifem::fem
