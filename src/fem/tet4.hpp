// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The linear 4-node tetrahedron. Shape functions N_a are linear, their gradients g_a constant:
/// with J = [x1 - x0, x2 - x0, x3 - x0], g_1..g_3 are the rows of J^-1 and g_0 = -(g_1 + g_2 + g_3).
/// Element stiffness K_e = V B^T D B, written per 3x3 node block (a, b) as
///   K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I).
#include <array>

#include "common/types.hpp"
#include "fem/material.hpp"

namespace roifem::fem {

struct Tet4Geometry {
  double volume = 0;                 ///< signed; positive for a correctly oriented element
  Eigen::Matrix<double, 4, 3> grad;  ///< row a = gradient of N_a
};

using ElementMatrix = Eigen::Matrix<double, 12, 12>;  ///< dof order: node a, component i -> 3a + i

Tet4Geometry tet4_geometry(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);
ElementMatrix tet4_stiffness(const Tet4Geometry& g, const Material& m);
/// The 3x3 block K_ab of tet4_stiffness (rows: node a's components, columns: node b's):
///   K_ab(i, j) = V (lambda ga_i gb_j + mu ga_j gb_i + mu (ga . gb) delta_ij).
/// The assembly's hot loop calls it, so it is written out entry by entry (docs/design-figures.md).
inline Mat3 tet4_stiffness_block(const Tet4Geometry& g, const Material& m, int a, int b) {
  const double V = std::abs(g.volume), lambda = m.lambda, mu = m.mu;
  const double ga[3] = {g.grad(a, 0), g.grad(a, 1), g.grad(a, 2)};
  const double gb[3] = {g.grad(b, 0), g.grad(b, 1), g.grad(b, 2)};
  const double shear = mu * (ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2]);
  Mat3 K_ab;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) K_ab(i, j) = V * (lambda * ga[i] * gb[j] + mu * ga[j] * gb[i] + (i == j ? shear : 0.0));
  return K_ab;
}
/// Strain (Voigt: xx, yy, zz, 2yz, 2xz, 2xy) from the 12 nodal displacements.
Eigen::Matrix<double, 6, 1> tet4_strain(const Tet4Geometry& g, const Eigen::Matrix<double, 12, 1>& u);

}  // namespace roifem::fem
