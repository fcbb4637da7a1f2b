// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/tet10.hpp"

#include "fem/tet4.hpp"

namespace roifem::fem {

namespace {

/// The 4-point rule of degree 2: L = b everywhere but a at one corner, weight 1/4 each.
constexpr double gauss_a = 0.5854101966249685, gauss_b = 0.1381966011250105;

}  // namespace

Tet10Geometry tet10_geometry(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Tet4Geometry linear = tet4_geometry(x0, x1, x2, x3);  // rows: grad L_i
  Tet10Geometry g;
  g.volume = linear.volume;
  for (int q = 0; q < 4; ++q) {
    Eigen::Vector4d L = Eigen::Vector4d::Constant(gauss_b);
    L[q] = gauss_a;
    auto& grad = g.grad[static_cast<std::size_t>(q)];
    for (int i = 0; i < 4; ++i) grad.row(i) = (4 * L[i] - 1) * linear.grad.row(i);
    for (std::size_t k = 0; k < tet10_edges.size(); ++k) {
      const int i = tet10_edges[k][0], j = tet10_edges[k][1];
      grad.row(4 + static_cast<int>(k)) = 4 * (L[i] * linear.grad.row(j) + L[j] * linear.grad.row(i));
    }
  }
  return g;
}

Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector4d& L) {
  Eigen::Matrix<double, 10, 1> N;
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2 * L[i] - 1);
  for (std::size_t k = 0; k < tet10_edges.size(); ++k)
    N[4 + static_cast<int>(k)] = 4 * L[tet10_edges[k][0]] * L[tet10_edges[k][1]];
  return N;
}

Mat3 tet10_stiffness_block(const Tet10Geometry& g, const Material& m, int a, int b) {
  Mat3 K = Mat3::Zero();
  for (const auto& grad : g.grad) {
    const Vec3 ga = grad.row(a).transpose(), gb = grad.row(b).transpose();
    K += m.lambda * ga * gb.transpose() + m.mu * gb * ga.transpose() + m.mu * ga.dot(gb) * Mat3::Identity();
  }
  return std::abs(g.volume) / 4 * K;
}

Tet10Matrix tet10_stiffness(const Tet10Geometry& g, const Material& m) {
  Tet10Matrix K;
  for (int a = 0; a < tet10_nodes; ++a)
    for (int b = 0; b < tet10_nodes; ++b) K.block<3, 3>(3 * a, 3 * b) = tet10_stiffness_block(g, m, a, b);
  return K;
}

}  // namespace roifem::fem
