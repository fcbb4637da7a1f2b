// SPDX-License-Identifier: GPL-3.0-or-later
// A manufactured solution on the unit cube converges at O(h^2) in L2 under uniform refinement.
//   u = (a_1, a_2, a_3) phi,  phi = 64 p(x) p(y) p(z),  p(t) = t (1 - t)   (zero on the boundary)
//   f = -div sigma(u) = -(lambda + mu) H a - mu (Laplacian phi) a,  H = Hessian of phi.
#include <gtest/gtest.h>

#include <cmath>

#include "fem/assembly.hpp"
#include "fem/static_solve.hpp"
#include "fem/tet4.hpp"
#include "mesh/box_mesh.hpp"

namespace roifem::fem {
namespace {

const Vec3 field_amplitude(1.0, -0.5, 0.75);

double p(double t) { return t * (1 - t); }
double phi(const Vec3& x) { return 64 * p(x.x()) * p(x.y()) * p(x.z()); }
Vec3 exact(const Vec3& x) { return field_amplitude * phi(x); }

Vec3 body_force(const Vec3& x, const Material& m) {
  const Vec3 v(p(x.x()), p(x.y()), p(x.z()));                 // p
  const Vec3 d(1 - 2 * x.x(), 1 - 2 * x.y(), 1 - 2 * x.z());  // p'
  Mat3 H;                                                     // p'' = -2
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int k = 3 - i - j;
      H(i, j) = i == j ? 64 * -2.0 * v[(i + 1) % 3] * v[(i + 2) % 3] : 64 * d[i] * d[j] * v[k];
    }
  return -(m.lambda + m.mu) * H * field_amplitude - m.mu * H.trace() * field_amplitude;
}

// Degree-2 four-point rule on a tetrahedron (barycentric a, b, b, b and permutations).
constexpr double qa = 0.5854101966249685, qb = 0.1381966011250105;
const double quadrature[4][4] = {{qa, qb, qb, qb}, {qb, qa, qb, qb}, {qb, qb, qa, qb}, {qb, qb, qb, qa}};

double l2_error(int n, const Material& m) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(n, n, n, 1, 1, 1);
  Constraints constraints(mesh.num_nodes());
  for (int node : mesh::boundary_nodes(mesh)) constraints.fix_node(node);
  const DofMap dofs(constraints);
  Vector f_full = Vector::Zero(3 * mesh.num_nodes());
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& t = mesh.tets[static_cast<std::size_t>(e)];
    const double V = mesh::signed_volume(mesh, e);
    for (const auto& w : quadrature) {
      Vec3 x = Vec3::Zero();
      for (int a = 0; a < 4; ++a) x += w[a] * mesh.node(t[static_cast<std::size_t>(a)]);
      const Vec3 fx = body_force(x, m);
      for (int a = 0; a < 4; ++a) f_full.segment<3>(3 * t[static_cast<std::size_t>(a)]) += V / 4 * w[a] * fx;
    }
  }
  const StiffnessAssembler assembler(mesh, dofs);
  const Vector u = dofs.expand(solve_static(assembler.stiffness(m), dofs.restrict_to_free(f_full), dofs));
  double err2 = 0;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& t = mesh.tets[static_cast<std::size_t>(e)];
    const double V = mesh::signed_volume(mesh, e);
    for (const auto& w : quadrature) {
      Vec3 x = Vec3::Zero(), uh = Vec3::Zero();
      for (int a = 0; a < 4; ++a) {
        x += w[a] * mesh.node(t[static_cast<std::size_t>(a)]);
        uh += w[a] * u.segment<3>(3 * t[static_cast<std::size_t>(a)]);
      }
      err2 += V / 4 * (uh - exact(x)).squaredNorm();
    }
  }
  return std::sqrt(err2);
}

TEST(Convergence, ManufacturedSolutionConvergesAtSecondOrderInL2) {
  const Material m = Material::from_young_poisson(3000, 0.3, 1000, 0);
  const int sizes[] = {8, 16, 32};  // 1/4 to 1/8 is still pre-asymptotic (order 1.79)
  double previous = 0;
  for (int n : sizes) {
    const double e = l2_error(n, m);
    if (previous > 0) {
      const double order = std::log(previous / e) / std::log(2.0);
      std::printf("h = 1/%-3d  L2 error %.4e  observed order %.3f\n", n, e, order);
      EXPECT_NEAR(order, 2.0, 0.1) << "between h = 1/" << n / 2 << " and 1/" << n;
    } else {
      std::printf("h = 1/%-3d  L2 error %.4e\n", n, e);
    }
    previous = e;
  }
}

}  // namespace
}  // namespace roifem::fem
