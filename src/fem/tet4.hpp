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
/// The 3x3 block K_ab of tet4_stiffness (rows: node a's components, columns: node b's).
inline Mat3 tet4_stiffness_block(const Tet4Geometry& g, const Material& m, int a, int b) {
  const Vec3 ga = g.grad.row(a).transpose(), gb = g.grad.row(b).transpose();
  return std::abs(g.volume) *
         (m.lambda * ga * gb.transpose() + m.mu * gb * ga.transpose() + m.mu * ga.dot(gb) * Mat3::Identity());
}
/// Strain (Voigt: xx, yy, zz, 2yz, 2xz, 2xy) from the 12 nodal displacements.
Eigen::Matrix<double, 6, 1> tet4_strain(const Tet4Geometry& g, const Eigen::Matrix<double, 12, 1>& u);

}  // namespace roifem::fem
