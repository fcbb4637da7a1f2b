// SPDX-License-Identifier: GPL-3.0-or-later
// The recovery error estimate (fem/recovery_estimate.hpp): zero where linear elements are exact,
// the energy norm it reports is u^T K u, and against Lame's solution it tracks the true energy error
// (computed here from the analytic strain by quadrature) with an effectivity near one, at the
// element's order.
#include "fem/recovery_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "experiments/lame_sphere.hpp"
#include "fem/dof_map.hpp"
#include "fem/tet4.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/sphere_shell_mesh.hpp"

namespace roifem::fem {
namespace {

Vector affine_field(const mesh::TetMesh& mesh) {
  Mat3 A;
  A << 1e-3, 2e-3, -1e-3, 0.5e-3, -2e-3, 3e-3, 1e-3, 1e-3, 4e-3;
  Vector u(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) u.segment<3>(3 * n) = A * mesh.node(n) + Vec3(1e-3, -2e-3, 0.5e-3);
  return u;
}

TEST(RecoveryEstimate, VanishesOnAnAffineFieldAndItsEnergyNormIsUKU) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(1.0, 0.8, 0.6, 0.25);
  const Material material = Material::from_young_poisson(3000, 0.45, 1000, 0);
  const Vector u = affine_field(mesh);
  const DofMap dofs{Constraints(mesh.num_nodes())};  // every dof free: K over all of them
  for (const Element element : {Element::tet4, Element::nodal_pressure}) {
    const RecoveryEstimate e = recovery_estimate(mesh, MaterialMap(material), element, u);
    EXPECT_LT(e.error, 1e-12 * e.energy_norm) << element_name(element);
    const SparseMatrix K = stiffness(mesh, dofs, material, element);
    const Vector free_u = dofs.restrict_to_free(u);
    EXPECT_NEAR(e.energy_norm * e.energy_norm, free_u.dot(K * free_u), 1e-10 * free_u.dot(K * free_u)) << element_name(element);
  }
  // A quadratic field is not exact: the estimate sees it.
  Vector quadratic = u;
  for (int n = 0; n < mesh.num_nodes(); ++n) quadratic[3 * n] += 1e-3 * mesh.node(n).squaredNorm();
  EXPECT_GT(recovery_estimate(mesh, MaterialMap(material), Element::tet4, quadratic).relative(), 1e-3);
}

/// The exact energy error ||u - u_h||_E on the mesh, with Lame's strain: grad u = f I + f'/r x x^T
/// for u = f(r) x, f = A + B / r^3; the 4-point rule of degree 2 on each tetrahedron.
double true_energy_error(const mesh::TetMesh& mesh, const experiments::LameSphere& s, const Vector& u_h) {
  const double a3 = std::pow(s.inner_radius, 3), b3 = std::pow(s.outer_radius, 3);
  const double c = s.pressure * a3 / (s.young * (b3 - a3));
  const double A = c * (1 - 2 * s.poisson), B = c * (1 + s.poisson) * b3 / 2;
  const Material m = Material::from_young_poisson(s.young, s.poisson, 1000, 0);
  const double alpha = 0.5854101966249685, beta = 0.1381966011250105;  // the points' barycentric weights
  double error2 = 0;
  for (const auto& t : mesh.tets) {
    const auto g = tet4_geometry(mesh.node(t[0]), mesh.node(t[1]), mesh.node(t[2]), mesh.node(t[3]));
    Mat3 grad_h = Mat3::Zero();
    for (int a = 0; a < 4; ++a) grad_h += u_h.segment<3>(3 * t[static_cast<std::size_t>(a)]) * g.grad.row(a);
    for (int q = 0; q < 4; ++q) {
      Vec3 x = Vec3::Zero();
      for (int a = 0; a < 4; ++a) x += (a == q ? alpha : beta) * mesh.node(t[static_cast<std::size_t>(a)]);
      const double r = x.norm();
      const Mat3 grad = (A + B / (r * r * r)) * Mat3::Identity() - 3 * B / std::pow(r, 5) * x * x.transpose();
      const Mat3 d = 0.5 * (grad - grad_h + (grad - grad_h).transpose());
      const double theta = d.trace();
      const Mat3 dev = d - theta / 3 * Mat3::Identity();
      error2 += std::abs(g.volume) / 4 * (2 * m.mu * dev.squaredNorm() + (m.lambda + 2 * m.mu / 3) * theta * theta);
    }
  }
  return std::sqrt(error2);
}

TEST(RecoveryEstimate, TracksTheTrueEnergyErrorOfLamesSphereAtTheElementsOrder) {
  const experiments::LameSphere sphere{.poisson = 0.3};
  const std::vector<double> sizes{0.004, 0.002, 0.001};
  std::vector<double> estimated, exact;
  std::printf("Lame sphere, tet4, nu = 0.3: energy error, estimated by recovery and true (effectivity)\n");
  for (double h : sizes) {
    const mesh::TetMesh mesh = mesh::sphere_shell_octant_mesh(0.01, 0.02, h);
    const Vector u = experiments::solve_lame_field(mesh, sphere);
    const Material m = Material::from_young_poisson(sphere.young, sphere.poisson, 1000, 0);
    estimated.push_back(recovery_estimate(mesh, MaterialMap(m), Element::tet4, u).error);
    exact.push_back(true_energy_error(mesh, sphere, u));
    std::printf("  %6lld nodes: %.4e  %.4e  (%.3f)\n", static_cast<long long>(mesh.num_nodes()), estimated.back(), exact.back(),
                estimated.back() / exact.back());
  }
  // Effectivity 0.815, 0.926, 0.963: nearing one as the mesh is refined.
  EXPECT_NEAR(estimated[1] / exact[1], 1.0, 0.15);
  EXPECT_NEAR(estimated[2] / exact[2], 1.0, 0.1);
  EXPECT_GT(estimated[2] / exact[2], estimated[0] / exact[0]);
  // Order 1 in h for linear elements (0.92 true, 0.86 estimated on the finest pair).
  const double order_true = std::log(exact[1] / exact[2]) / std::log(2.0);
  const double order_estimated = std::log(estimated[1] / estimated[2]) / std::log(2.0);
  EXPECT_NEAR(order_true, 1.0, 0.15);
  EXPECT_NEAR(order_estimated, order_true, 0.1);
}

}  // namespace
}  // namespace roifem::fem
