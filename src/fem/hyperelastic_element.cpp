// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/hyperelastic_element.hpp"

#include <algorithm>
#include <cmath>

namespace roifem::fem {

namespace {

/// The quadrature over `points` points, each with its gradients (Nodes x 3) and weight.
template <int Nodes, int Points>
HyperelasticResponse<Nodes> integrate_element(const std::array<Eigen::Matrix<double, Nodes, 3>, Points>& grads, double weight,
                                              const NeoHookean& law, const Eigen::Matrix<double, 3 * Nodes, 1>& u_e,
                                              Evaluate what) {
  HyperelasticResponse<Nodes> r;
  // The displacement gradients H = F - I first (the law takes H: neo_hookean.hpp), so that an
  // inverted element computes nothing.
  std::array<Mat3, Points> H;
  for (int q = 0; q < Points; ++q) {
    H[q].setZero();
    for (int a = 0; a < Nodes; ++a) H[q] += u_e.template segment<3>(3 * a) * grads[q].row(a);
    r.min_J = std::min(r.min_J, 1 + NeoHookean::J_minus_1(H[q]));
  }
  if (!(r.min_J > 0)) return r;
  r.force.setZero();
  const bool tangent = what == Evaluate::force_and_tangent;
  if (tangent) r.tangent.setZero();
  Mat3 P;
  Mat9 A;
  for (int q = 0; q < Points; ++q) {
    const auto& g = grads[q];
    r.energy += weight * law.energy(H[q]);
    if (!tangent) {
      P = law.stress(H[q]);
    } else {
      law.stress_and_tangent(H[q], P, A);
    }
    // f_a = w P g_a: the 3 x Nodes block P G^T.
    const Eigen::Matrix<double, 3, Nodes> PG = weight * P * g.transpose();
    for (int a = 0; a < Nodes; ++a) r.force.template segment<3>(3 * a) += PG.col(a);
    if (!tangent) continue;
    // K_ab(i, k) = w sum_{J,L} A(3i+J, 3k+L) g_aJ g_bL. First H_a(i, 3k+L) = sum_J A(3i+J, 3k+L) g_aJ.
    for (int a = 0; a < Nodes; ++a) {
      Eigen::Matrix<double, 3, 9> H;
      for (int i = 0; i < 3; ++i) H.row(i) = g(a, 0) * A.row(3 * i) + g(a, 1) * A.row(3 * i + 1) + g(a, 2) * A.row(3 * i + 2);
      for (int b = 0; b < Nodes; ++b)
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d gb = g.row(b).transpose();
          r.tangent.template block<3, 1>(3 * a, 3 * b + k) += weight * H.template middleCols<3>(3 * k) * gb;
        }
    }
  }
  return r;
}

}  // namespace

HyperelasticResponse<4> tet4_hyperelastic(const Tet4Geometry& g, const NeoHookean& law, const Eigen::Matrix<double, 12, 1>& u_e,
                                          Evaluate what) {
  return integrate_element<4, 1>({g.grad}, std::abs(g.volume), law, u_e, what);
}

HyperelasticResponse<10> tet10_hyperelastic(const Tet10Geometry& g, const NeoHookean& law,
                                            const Eigen::Matrix<double, 30, 1>& u_e, Evaluate what) {
  return integrate_element<10, 4>(g.grad, std::abs(g.volume) / 4, law, u_e, what);
}

}  // namespace roifem::fem
