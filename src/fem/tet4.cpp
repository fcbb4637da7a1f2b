// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/tet4.hpp"

#include <Eigen/LU>

namespace roifem::fem {

Tet4Geometry tet4_geometry(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Mat3 J;
  J << x1 - x0, x2 - x0, x3 - x0;
  Tet4Geometry g;
  g.volume = J.determinant() / 6.0;
  const Mat3 Jinv = J.inverse();
  g.grad.row(1) = Jinv.row(0);
  g.grad.row(2) = Jinv.row(1);
  g.grad.row(3) = Jinv.row(2);
  g.grad.row(0) = -(Jinv.row(0) + Jinv.row(1) + Jinv.row(2));
  return g;
}

ElementMatrix tet4_stiffness(const Tet4Geometry& g, const Material& m) {
  ElementMatrix K;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) K.block<3, 3>(3 * a, 3 * b) = tet4_stiffness_block(g, m, a, b);
  return K;
}

Eigen::Matrix<double, 6, 1> tet4_strain(const Tet4Geometry& g, const Eigen::Matrix<double, 12, 1>& u) {
  Mat3 grad_u = Mat3::Zero();  // (i, j) = d u_i / d x_j
  for (int a = 0; a < 4; ++a) grad_u += u.segment<3>(3 * a) * g.grad.row(a);
  Eigen::Matrix<double, 6, 1> e;
  e << grad_u(0, 0), grad_u(1, 1), grad_u(2, 2), grad_u(1, 2) + grad_u(2, 1), grad_u(0, 2) + grad_u(2, 0),
      grad_u(0, 1) + grad_u(1, 0);
  return e;
}

}  // namespace roifem::fem
