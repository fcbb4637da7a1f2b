// SPDX-License-Identifier: GPL-3.0-or-later
// Lame's thick-walled sphere under internal pressure (experiments/lame_sphere.hpp): the linear
// tetrahedron against the analytic solution, refined, at nu = 0.3 and nearly incompressible.
#include "experiments/lame_sphere.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
#include "experiments/calculix_static.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "mesh/sphere_shell_mesh.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

TEST(LameSphere, LinearTetrahedraConvergeAtSecondOrderAndLockAsNuNearsOneHalf) {
  const std::vector<double> sizes{0.004, 0.002, 0.001};  // m, on a shell 10 mm thick
  std::vector<mesh::TetMesh> meshes;
  for (double h : sizes) {
    meshes.push_back(mesh::sphere_shell_octant_mesh(0.01, 0.02, h));
    mesh::check_mesh(meshes.back());
  }
  const std::vector<double> poissons{0.3, 0.49, 0.499, 0.4999};
  std::vector<std::vector<LameError>> errors;
  std::printf("Lame sphere (a = 10 mm, b = 20 mm, octant), linear tetrahedra: relative nodal L2 error (order)\n%8s", "nodes");
  for (double nu : poissons) std::printf("   nu = %-14g", nu);
  std::printf("\n");
  for (double nu : poissons) {
    errors.emplace_back();
    for (const auto& m : meshes) errors.back().push_back(solve_lame_sphere(m, LameSphere{.poisson = nu}));
  }
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    std::printf("%8lld", static_cast<long long>(meshes[k].num_nodes()));
    for (std::size_t j = 0; j < poissons.size(); ++j) {
      const double e = errors[j][k].l2;
      if (k == 0)
        std::printf("   %9.3e        ", e);
      else
        std::printf("   %9.3e (%4.2f) ", e, std::log(errors[j][k - 1].l2 / e) / std::log(sizes[k - 1] / sizes[k]));
    }
    std::printf("\n");
  }
  std::printf("inner face's mean radial displacement, finest mesh, relative error:");
  for (std::size_t j = 0; j < poissons.size(); ++j) std::printf(" %+.3f", errors[j].back().inner_mean);
  std::printf("\n");

  // Compressible: second order in the nodal L2 error, and close on the finest mesh.
  const double order = std::log(errors[0][1].l2 / errors[0][2].l2) / std::log(2.0);
  EXPECT_NEAR(order, 2.0, 0.4);
  EXPECT_LT(errors[0].back().l2, 0.02);
  // Nearly incompressible: the same meshes lock, the displacement far too small.
  EXPECT_GT(errors[3].back().l2, 10 * errors[0].back().l2);
  EXPECT_LT(errors[3].back().inner_mean, -0.2);
  for (std::size_t j = 1; j < poissons.size(); ++j) EXPECT_GT(errors[j].back().l2, errors[j - 1].back().l2) << poissons[j];
}

TEST(LameSphere, RefusesAShellThatCannotBeMeshed) {
  EXPECT_THROW(mesh::sphere_shell_octant_mesh(0.02, 0.01, 0.001), InputError);
  EXPECT_THROW(mesh::sphere_shell_octant_mesh(0.01, 0.02, 0.02), InputError);
}

TEST(LameSphere, Tet10DoesNotLockAndConvergesAtSecondOrder) {
  // roifem's own 10-node tetrahedron on two meshes: bounded as nu nears 1/2, and second order in
  // the nodal error (the faceted inner surface holds it there; the table: DISABLED_ElementTable).
  std::vector<LameError> compressible, incompressible;
  for (const double h : {0.004, 0.002}) {
    const mesh::TetMesh q = mesh::with_midside_nodes(mesh::sphere_shell_octant_mesh(0.01, 0.02, h));
    compressible.push_back(solve_lame_sphere(q, {.poisson = 0.3}));
    incompressible.push_back(solve_lame_sphere(q, {.poisson = 0.4999}));
  }
  std::printf("tet10: nu 0.3 %.3e, %.3e; nu 0.4999 %.3e, %.3e\n", compressible[0].l2, compressible[1].l2, incompressible[0].l2,
              incompressible[1].l2);
  EXPECT_LT(incompressible[1].l2, 2 * compressible[1].l2);
  EXPECT_LT(incompressible[1].l2, 0.05);
  EXPECT_GT(std::log2(incompressible[0].l2 / incompressible[1].l2), 1.7);
  EXPECT_LT(std::abs(incompressible[1].inner_mean), 0.05);
}

TEST(LameSphere, Tet10EqualsCalculixC3d10OnTheSameMesh) {
  // Two independent implementations of the same element, loads and supports: roifem's
  // assembled K solved by CHOLMOD, and CalculiX's C3D10 solved by SPOOLES.
  if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  const test::TempDir dir;
  const mesh::TetMesh mesh = mesh::sphere_shell_octant_mesh(0.01, 0.02, 0.004);
  for (const double nu : {0.3, 0.4999}) {
    const LameError roifem = solve_lame_sphere(mesh::with_midside_nodes(mesh), {.poisson = nu});
    const LameError ccx = solve_lame_sphere_c3d10(mesh, {.poisson = nu}, dir.path());
    std::printf("nu = %g: tet10 %.6e, C3D10 %.6e (relative nodal L2 error)\n", nu, roifem.l2, ccx.l2);
    EXPECT_NEAR(roifem.l2, ccx.l2, 1e-5 * ccx.l2) << nu;
    EXPECT_NEAR(roifem.inner_mean, ccx.inner_mean, 1e-5) << nu;
  }
}

TEST(LameSphere, QuadraticTetrahedraDoNotLock) {
  if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  const test::TempDir dir;
  const mesh::TetMesh mesh = mesh::sphere_shell_octant_mesh(0.01, 0.02, 0.004);
  const LameError c3d10 = solve_lame_sphere_c3d10(mesh, {.poisson = 0.3}, dir.path());
  const LameError c3d10_incompressible = solve_lame_sphere_c3d10(mesh, {.poisson = 0.4999}, dir.path());
  const LameError tet4 = solve_lame_sphere(mesh, {.poisson = 0.3});
  const LameError tet4_incompressible = solve_lame_sphere(mesh, {.poisson = 0.4999});
  std::printf("148-node octant: C3D10 %.3e (nu 0.3), %.3e (nu 0.4999); tet4 %.3e, %.3e\n", c3d10.l2, c3d10_incompressible.l2,
              tet4.l2, tet4_incompressible.l2);
  EXPECT_LT(c3d10.l2, 0.5 * tet4.l2);                // 0.0675 against 0.159
  EXPECT_LT(c3d10_incompressible.l2, 2 * c3d10.l2);  // 0.106: bounded as nu nears 1/2
  EXPECT_GT(tet4_incompressible.l2, 5 * tet4.l2);    // 0.943: locked
  EXPECT_LT(std::abs(c3d10_incompressible.inner_mean), 0.15);
}

/// Quadratic tetrahedra (CalculiX C3D10, straight-sided on the same meshes: the other candidate
/// against locking). Run with --gtest_also_run_disabled_tests
/// --gtest_filter=LameSphere.DISABLED_ElementTable (a few minutes): per nu and element, the
/// relative nodal L2 error with its order, and the dofs.
TEST(LameSphere, DISABLED_ElementTable) {
  if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed";
  const test::TempDir dir;
  const std::vector<double> sizes{0.004, 0.002, 0.001};
  std::vector<mesh::TetMesh> meshes;
  meshes.reserve(sizes.size());
  for (double h : sizes) meshes.push_back(mesh::sphere_shell_octant_mesh(0.01, 0.02, h));
  std::printf("Lame sphere, relative nodal L2 error (order) [dofs], by element:\n");
  for (const double nu : {0.3, 0.49, 0.499, 0.4999})
    for (const char* element : {"tet4", "nodal-pressure", "tet10", "c3d10"}) {
      std::printf("  nu = %-7g %-15s", nu, element);
      double previous = 0;
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        const LameSphere sphere{.poisson = nu};
        const std::string e_name = element;
        const bool quadratic = e_name == "c3d10" || e_name == "tet10";
        const double e = e_name == "c3d10"   ? solve_lame_sphere_c3d10(meshes[k], sphere, dir.path()).l2
                         : e_name == "tet10" ? solve_lame_sphere(mesh::with_midside_nodes(meshes[k]), sphere).l2
                         : e_name == "tet4"  ? solve_lame_sphere(meshes[k], sphere).l2
                                             : solve_lame_sphere(meshes[k], sphere, 0.0).l2;
        const Index nodes = quadratic ? mesh::with_midside_nodes(meshes[k]).num_nodes() : meshes[k].num_nodes();
        std::printf("  %9.3e", e);
        std::printf(k > 0 ? " (%4.2f)" : "       ", k > 0 ? std::log(previous / e) / std::log(sizes[k - 1] / sizes[k]) : 0.0);
        std::printf(" [%6lld]", 3 * static_cast<long long>(nodes));
        previous = e;
      }
      std::printf("\n");
    }
}

}  // namespace
}  // namespace roifem::experiments
