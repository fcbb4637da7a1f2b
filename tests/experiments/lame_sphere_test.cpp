// Lame's thick-walled sphere under internal pressure (experiments/lame_sphere.hpp): the linear
// tetrahedron against the analytic solution, refined, at nu = 0.3 and nearly incompressible.
#include "experiments/lame_sphere.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/sphere_shell_mesh.hpp"

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

}  // namespace
}  // namespace roifem::experiments
