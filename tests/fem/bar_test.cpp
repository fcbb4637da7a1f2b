// SPDX-License-Identifier: GPL-3.0-or-later
// A prismatic bar in uniaxial tension: u_x(L) = F L / (E A), lateral contraction nu.
// Linear displacements lie in the P1 space, so the finite element answer is exact.
#include <gtest/gtest.h>

#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "fem/static_solve.hpp"
#include "mesh/box_mesh.hpp"

namespace roifem::fem {
namespace {

TEST(UniaxialBar, ElongationAndLateralContractionMatchTheory) {
  const double L = 0.1, a = 0.01, b = 0.02, E = 5e4, nu = 0.3, F = 2.0;
  const mesh::TetMesh mesh = mesh::structured_box_mesh(20, 2, 3, L, a, b);
  // Symmetry planes: u_x = 0 on x = 0, u_y = 0 on y = 0, u_z = 0 on z = 0; nothing else is held.
  Constraints constraints(mesh.num_nodes());
  for (int n : mesh.set("x0").nodes) constraints.prescribe(n, 0);
  for (int n : mesh.set("y0").nodes) constraints.prescribe(n, 1);
  for (int n : mesh.set("z0").nodes) constraints.prescribe(n, 2);
  const DofMap dofs(constraints);
  const Material material = Material::from_young_poisson(E, nu, 1000, 0);
  const StiffnessAssembler assembler(mesh, dofs);
  const Vector f = dofs.restrict_to_free(set_force(mesh, "x1", Vec3(F, 0, 0)));
  const Vector u = dofs.expand(solve_static(assembler.stiffness(material), f, dofs));

  const double strain = F / (E * a * b);
  double worst = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 x = mesh.node(n);
    const Vec3 exact(strain * x.x(), -nu * strain * x.y(), -nu * strain * x.z());
    worst = std::max(worst, (u.segment<3>(3 * n) - exact).norm());
  }
  const double elongation = strain * L;
  EXPECT_LT(worst / elongation, 1e-10);
  // The quantities the textbook names, at the loaded end's far corner.
  int corner = -1;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if ((mesh.node(n) - Vec3(L, a, b)).norm() < 1e-12) corner = n;
  ASSERT_GE(corner, 0);
  EXPECT_NEAR(u[3 * corner] / elongation, 1.0, 1e-10);
  EXPECT_NEAR(-(u[3 * corner + 1] / a) / (u[3 * corner] / L), nu, 1e-10);
  std::printf("bar: u_x(L) = %.12e m (F L / E A = %.12e), relative error %.2e; lateral ratio %.12f\n", u[3 * corner], elongation,
              worst / elongation, -(u[3 * corner + 1] / a) / (u[3 * corner] / L));
}

}  // namespace
}  // namespace roifem::fem
