// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/hyperelastic_element.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace roifem::fem {

namespace {

/// K_ab(i, k) += w sum_{J,L} A(3i+J, 3k+L) g_aJ g_bL: a quadrature point's share of the element
/// matrix, for A = dP/dF over the flattened F (row-major).
template <int Nodes>
void add_tangent(const Mat9& A, const Eigen::Matrix<double, Nodes, 3>& g, double weight,
                 Eigen::Matrix<double, 3 * Nodes, 3 * Nodes>& K) {
  // First Ag_a(i, 3k+L) = sum_J A(3i+J, 3k+L) g_aJ.
  for (int a = 0; a < Nodes; ++a) {
    Eigen::Matrix<double, 3, 9> Ag;
    for (int i = 0; i < 3; ++i) Ag.row(i) = g(a, 0) * A.row(3 * i) + g(a, 1) * A.row(3 * i + 1) + g(a, 2) * A.row(3 * i + 2);
    for (int b = 0; b < Nodes; ++b)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d gb = g.row(b).transpose();
        K.template block<3, 1>(3 * a, 3 * b + k) += weight * Ag.template middleCols<3>(3 * k) * gb;
      }
  }
}

/// The quadrature over `points` points, each with its gradients (Nodes x 3) and weight.
template <int Nodes, int Points, class Law>
HyperelasticResponse<Nodes> integrate_element(const std::array<Eigen::Matrix<double, Nodes, 3>, Points>& grads, double weight,
                                              const Law& law, const Eigen::Matrix<double, 3 * Nodes, 1>& u_e, Evaluate what) {
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
    if (what == Evaluate::energy) r.energy += weight * law.energy(H[q]);
    if (tangent)
      law.stress_and_tangent(H[q], P, A);
    else if (what == Evaluate::excess)
      P = law.excess_stress(H[q]);
    else
      P = law.stress(H[q]);
    // f_a = w P g_a: the 3 x Nodes block P G^T.
    const Eigen::Matrix<double, 3, Nodes> PG = weight * P * g.transpose();
    for (int a = 0; a < Nodes; ++a) r.force.template segment<3>(3 * a) += PG.col(a);
    if (tangent) add_tangent<Nodes>(A, g, weight, r.tangent);
  }
  return r;
}

/// The displacement gradient sum_a u_a g_a^T at one quadrature point.
template <int Nodes>
Mat3 gradient_of(const Eigen::Matrix<double, Nodes, 3>& g, const Eigen::Matrix<double, 3 * Nodes, 1>& u_e) {
  Mat3 H = Mat3::Zero();
  for (int a = 0; a < Nodes; ++a) H += u_e.template segment<3>(3 * a) * g.row(a);
  return H;
}

/// d(F_mid S_alg)/dF_b over the flattened F_b (row-major), with D = dS_alg/dE_b:
///   dP = dF S_alg / 2 + F_mid (D . vec(sym(F_b^T dF))).
Mat9 discrete_gradient_tangent(const Mat3& F_mid, const Mat3& F_b, const Mat3& S_alg, const Mat9& D) {
  // DF(3M+J, 3k+L) = sum_{P,Q} D(3M+J, 3P+Q) (F_b(k,P) d_QL + F_b(k,Q) d_PL) / 2.
  Mat9 DF;
  for (int row = 0; row < 9; ++row)
    for (int k = 0; k < 3; ++k)
      for (int L = 0; L < 3; ++L) {
        double v = 0;
        for (int P = 0; P < 3; ++P) v += (D(row, 3 * P + L) + D(row, 3 * L + P)) * F_b(k, P);
        DF(row, 3 * k + L) = 0.5 * v;
      }
  Mat9 A;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int col = 0; col < 9; ++col) {
        double v = 0;
        for (int M = 0; M < 3; ++M) v += F_mid(i, M) * DF(3 * M + J, col);
        A(3 * i + J, col) = v;
      }
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int L = 0; L < 3; ++L) A(3 * i + J, 3 * i + L) += 0.5 * S_alg(L, J);
  return A;
}

template <int Nodes, int Points, class Law>
HyperelasticResponse<Nodes> integrate_discrete_gradient(const std::array<Eigen::Matrix<double, Nodes, 3>, Points>& grads,
                                                        double weight, const Law& law,
                                                        const Eigen::Matrix<double, 3 * Nodes, 1>& u_a,
                                                        const Eigen::Matrix<double, 3 * Nodes, 1>& u_b, Evaluate what) {
  HyperelasticResponse<Nodes> r;
  std::array<Mat3, Points> H_a, H_b;
  for (int q = 0; q < Points; ++q) {
    H_a[q] = gradient_of<Nodes>(grads[q], u_a);
    H_b[q] = gradient_of<Nodes>(grads[q], u_b);
    r.min_J = std::min({r.min_J, 1 + NeoHookean::J_minus_1(H_a[q]), 1 + NeoHookean::J_minus_1(H_b[q])});
  }
  if (!(r.min_J > 0)) return r;
  r.force.setZero();
  const bool tangent = what == Evaluate::force_and_tangent;
  if (tangent) r.tangent.setZero();
  Mat9 D;
  for (int q = 0; q < Points; ++q) {
    r.energy += weight * law.energy(H_b[q]);
    const Mat3 F_mid = Mat3::Identity() + 0.5 * (H_a[q] + H_b[q]);
    const Mat3 S_alg = tangent ? discrete_gradient_stress(law, H_a[q], H_b[q], D) : discrete_gradient_stress(law, H_a[q], H_b[q]);
    const Eigen::Matrix<double, 3, Nodes> PG = weight * F_mid * S_alg * grads[q].transpose();
    for (int a = 0; a < Nodes; ++a) r.force.template segment<3>(3 * a) += PG.col(a);
    if (tangent)
      add_tangent<Nodes>(discrete_gradient_tangent(F_mid, Mat3::Identity() + H_b[q], S_alg, D), grads[q], weight, r.tangent);
  }
  return r;
}

}  // namespace

template <class Law>
HyperelasticResponse<4> tet4_discrete_gradient(const Tet4Geometry& g, const Law& law, const Eigen::Matrix<double, 12, 1>& u_a,
                                               const Eigen::Matrix<double, 12, 1>& u_b, Evaluate what) {
  return integrate_discrete_gradient<4, 1>({g.grad}, std::abs(g.volume), law, u_a, u_b, what);
}

template <class Law>
HyperelasticResponse<10> tet10_discrete_gradient(const Tet10Geometry& g, const Law& law, const Eigen::Matrix<double, 30, 1>& u_a,
                                                 const Eigen::Matrix<double, 30, 1>& u_b, Evaluate what) {
  return integrate_discrete_gradient<10, 4>(g.grad, std::abs(g.volume) / 4, law, u_a, u_b, what);
}

template <class Law>
HyperelasticResponse<4> tet4_hyperelastic(const Tet4Geometry& g, const Law& law, const Eigen::Matrix<double, 12, 1>& u_e,
                                          Evaluate what) {
  if constexpr (std::is_same_v<Law, NeoHookean>)
    if (what == Evaluate::excess) {
      HyperelasticResponse<4> r;
      r.force.setZero();
      r.min_J = tet4_excess_force(g, law, u_e, r.force);
      return r;
    }
  return integrate_element<4, 1>({g.grad}, std::abs(g.volume), law, u_e, what);
}

double tet4_excess_force(const Tet4Geometry& g, const NeoHookean& law, const Eigen::Matrix<double, 12, 1>& u_e,
                         Eigen::Matrix<double, 12, 1>& excess) {
  Mat3 H = Mat3::Zero();
  for (int a = 0; a < 4; ++a) H.noalias() += u_e.segment<3>(3 * a) * g.grad.row(a);
  const double J_minus_1 = NeoHookean::J_minus_1(H);
  const double J = 1 + J_minus_1;
  if (!(J > 0)) return J;
  const Mat3 F = Mat3::Identity() + H;
  Mat3 cofactor;  // cof(F) = J F^-T
  cofactor.col(0) = F.col(1).cross(F.col(2));
  cofactor.col(1) = F.col(2).cross(F.col(0));
  cofactor.col(2) = F.col(0).cross(F.col(1));
  const double mu = 2 * law.C10, kappa = 2 / law.D1, lambda = kappa - 2.0 / 3.0 * mu;
  Mat3 S = H + H.transpose();  // 2E = H + H^T + H^T H; S = mu J^(-2/3) dev(2E) + kappa (J - 1) J I
  S.noalias() += H.transpose() * H;
  const double third_trace = S.trace() / 3, root = std::cbrt(J);
  S.diagonal().array() -= third_trace;
  S *= mu / (root * root);
  S.diagonal().array() += kappa * J_minus_1 * J;
  Mat3 X = (cofactor * S) / J;  // P = F^-T S
  X -= mu * (H + H.transpose());
  X.diagonal().array() -= lambda * H.trace();
  X *= std::abs(g.volume);
  for (int a = 0; a < 4; ++a) excess.segment<3>(3 * a).noalias() = X * g.grad.row(a).transpose();
  return J;
}

template <class Law>
HyperelasticResponse<10> tet10_hyperelastic(const Tet10Geometry& g, const Law& law, const Eigen::Matrix<double, 30, 1>& u_e,
                                            Evaluate what) {
  return integrate_element<10, 4>(g.grad, std::abs(g.volume) / 4, law, u_e, what);
}

// Each law's elements, compiled here once.
#define ROIFEM_HYPERELASTIC_ELEMENTS(Law)                                                                                       \
  template HyperelasticResponse<4> tet4_hyperelastic(const Tet4Geometry&, const Law&, const Eigen::Matrix<double, 12, 1>&,      \
                                                     Evaluate);                                                                 \
  template HyperelasticResponse<10> tet10_hyperelastic(const Tet10Geometry&, const Law&, const Eigen::Matrix<double, 30, 1>&,   \
                                                       Evaluate);                                                               \
  template HyperelasticResponse<4> tet4_discrete_gradient(const Tet4Geometry&, const Law&, const Eigen::Matrix<double, 12, 1>&, \
                                                          const Eigen::Matrix<double, 12, 1>&, Evaluate);                       \
  template HyperelasticResponse<10> tet10_discrete_gradient(                                                                    \
      const Tet10Geometry&, const Law&, const Eigen::Matrix<double, 30, 1>&, const Eigen::Matrix<double, 30, 1>&, Evaluate);
ROIFEM_HYPERELASTIC_ELEMENTS(NeoHookean)
ROIFEM_HYPERELASTIC_ELEMENTS(Ogden)
#undef ROIFEM_HYPERELASTIC_ELEMENTS

}  // namespace roifem::fem
