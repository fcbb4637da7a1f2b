// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/tet4_excess_batch.hpp"

#include <cmath>

namespace roifem::fem {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ROIFEM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define ROIFEM_VECTOR_CLONES
#endif

ROIFEM_VECTOR_CLONES
void tet4_excess_force_batch(const Tet4ExcessBatch& b, const double (&u)[12][kTet4Lanes], double (&excess)[12][kTet4Lanes],
                             double (&J)[kTet4Lanes]) {
  double H[3][3][kTet4Lanes];  // H_ij = sum_a u_a,i dN_a/dx_j
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
#pragma omp simd
      for (int l = 0; l < kTet4Lanes; ++l)
        H[i][j][l] = u[i][l] * b.grad[0][j][l] + u[3 + i][l] * b.grad[1][j][l] + u[6 + i][l] * b.grad[2][j][l] +
                     u[9 + i][l] * b.grad[3][j][l];
  double J_minus_1[kTet4Lanes], root[kTet4Lanes];
#pragma omp simd
  for (int l = 0; l < kTet4Lanes; ++l) {
    // det(I + H) - 1 = tr H + ((tr H)^2 - tr H^2)/2 + det H, without cancellation (NeoHookean::J_minus_1).
    const double h00 = H[0][0][l], h01 = H[0][1][l], h02 = H[0][2][l];
    const double h10 = H[1][0][l], h11 = H[1][1][l], h12 = H[1][2][l];
    const double h20 = H[2][0][l], h21 = H[2][1][l], h22 = H[2][2][l];
    const double tr = h00 + h11 + h22;
    const double tr_H2 = h00 * h00 + h11 * h11 + h22 * h22 + 2 * (h01 * h10 + h02 * h20 + h12 * h21);
    const double det = h00 * (h11 * h22 - h12 * h21) - h01 * (h10 * h22 - h12 * h20) + h02 * (h10 * h21 - h11 * h20);
    J_minus_1[l] = tr + 0.5 * (tr * tr - tr_H2) + det;
    J[l] = 1 + J_minus_1[l];
    // J^(1/3) by Halley's iteration r <- r (r^3 + 2J) / (2 r^3 + J) from 1: cubic convergence, at
    // rounding after four steps for J in [1/4, 4] (the first step's error is below 6%).
    const double j = J[l];  // an inverted element's (j <= 0) answers are meaningless, and unread
    const auto halley = [j](double r) {
      const double r3 = r * r * r;
      return r * (r3 + 2 * j) / (2 * r3 + j);
    };
    const double r = halley(halley(halley(halley(1.0))));
    root[l] = r;
  }
  for (int l = 0; l < kTet4Lanes; ++l)
    if (J[l] > 0 && (J[l] < 0.25 || J[l] > 4)) root[l] = std::cbrt(J[l]);  // rare: far from the iteration's range
#pragma omp simd
  for (int l = 0; l < kTet4Lanes; ++l) {
    const double h00 = H[0][0][l], h01 = H[0][1][l], h02 = H[0][2][l];
    const double h10 = H[1][0][l], h11 = H[1][1][l], h12 = H[1][2][l];
    const double h20 = H[2][0][l], h21 = H[2][1][l], h22 = H[2][2][l];
    const double f00 = 1 + h00, f11 = 1 + h11, f22 = 1 + h22;
    // cof(F) = J F^-T, column by column: F's columns crossed.
    const double c00 = f11 * f22 - h21 * h12, c10 = h21 * h02 - h01 * f22, c20 = h01 * h12 - f11 * h02;
    const double c01 = h12 * h20 - h10 * f22, c11 = f22 * f00 - h20 * h02, c21 = h02 * h10 - h12 * f00;
    const double c02 = h10 * h21 - f11 * h20, c12 = h20 * h01 - f00 * h21, c22 = f00 * f11 - h10 * h01;
    // 2E = H + H^T + H^T H (symmetric).
    double s00 = 2 * h00 + h00 * h00 + h10 * h10 + h20 * h20;
    double s11 = 2 * h11 + h01 * h01 + h11 * h11 + h21 * h21;
    double s22 = 2 * h22 + h02 * h02 + h12 * h12 + h22 * h22;
    double s01 = h01 + h10 + h00 * h01 + h10 * h11 + h20 * h21;
    double s02 = h02 + h20 + h00 * h02 + h10 * h12 + h20 * h22;
    double s12 = h12 + h21 + h01 * h02 + h11 * h12 + h21 * h22;
    // S = mu J^(-2/3) dev(2E) + kappa (J - 1) J I.
    const double third = (s00 + s11 + s22) / 3;
    const double a = b.mu[l] / (root[l] * root[l]), p = b.kappa[l] * J_minus_1[l] * J[l];
    s00 = a * (s00 - third) + p;
    s11 = a * (s11 - third) + p;
    s22 = a * (s22 - third) + p;
    s01 *= a;
    s02 *= a;
    s12 *= a;
    // X = V [cof(F) S / J - mu (H + H^T) - lambda tr(H) I]: P = F^-T S less the linear stress.
    const double inv_J = 1 / J[l], mu = b.mu[l], lt = b.lambda[l] * (h00 + h11 + h22), V = b.volume[l];
    const double x00 = V * ((c00 * s00 + c01 * s01 + c02 * s02) * inv_J - 2 * mu * h00 - lt);
    const double x01 = V * ((c00 * s01 + c01 * s11 + c02 * s12) * inv_J - mu * (h01 + h10));
    const double x02 = V * ((c00 * s02 + c01 * s12 + c02 * s22) * inv_J - mu * (h02 + h20));
    const double x10 = V * ((c10 * s00 + c11 * s01 + c12 * s02) * inv_J - mu * (h10 + h01));
    const double x11 = V * ((c10 * s01 + c11 * s11 + c12 * s12) * inv_J - 2 * mu * h11 - lt);
    const double x12 = V * ((c10 * s02 + c11 * s12 + c12 * s22) * inv_J - mu * (h12 + h21));
    const double x20 = V * ((c20 * s00 + c21 * s01 + c22 * s02) * inv_J - mu * (h20 + h02));
    const double x21 = V * ((c20 * s01 + c21 * s11 + c22 * s12) * inv_J - mu * (h21 + h12));
    const double x22 = V * ((c20 * s02 + c21 * s12 + c22 * s22) * inv_J - 2 * mu * h22 - lt);
    const auto node_force = [&](int node) {  // X times the node's gradient
      const double g0 = b.grad[node][0][l], g1 = b.grad[node][1][l], g2 = b.grad[node][2][l];
      excess[3 * node][l] = x00 * g0 + x01 * g1 + x02 * g2;
      excess[3 * node + 1][l] = x10 * g0 + x11 * g1 + x12 * g2;
      excess[3 * node + 2][l] = x20 * g0 + x21 * g1 + x22 * g2;
    };
    node_force(0);
    node_force(1);
    node_force(2);
    node_force(3);
  }
}

#undef ROIFEM_VECTOR_CLONES

}  // namespace roifem::fem
