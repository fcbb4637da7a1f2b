// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The straight-sided 10-node tetrahedron (quadratic displacement; mesh/quadratic_mesh.hpp). In the
/// barycentric coordinates L_0..L_3 of its corners, N_i = L_i (2 L_i - 1) at corner i and
/// N_ij = 4 L_i L_j at the midpoint of edge (i, j); nodes 4-9 are the midpoints of edges
/// (0 1), (1 2), (2 0), (0 3), (1 3), (2 3). The gradients are linear, so the stiffness integrand is
/// quadratic and the 4-point Gauss rule (degree 2) integrates it exactly:
///   K_ab = sum_q V/4 (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I),  g = grad N at point q.
/// The lumped mass is HRZ's (Hinton, Rock & Zienkiewicz 1976): the consistent mass's diagonal
/// (rho V/70 at a corner, 8 rho V/105 at a midpoint) scaled to the element's mass, which gives
/// rho V/36 to each corner and 4 rho V/27 to each midpoint, all positive. (The row sums would give
/// the corners -rho V/20.)
#include <array>

#include "common/types.hpp"
#include "fem/material.hpp"

namespace roifem::fem {

constexpr int tet10_nodes = 10;
/// The corners of the edge each midside node 4..9 sits on.
constexpr std::array<std::array<int, 2>, 6> tet10_edges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
/// HRZ lumped mass fractions of rho V.
constexpr double tet10_corner_mass = 1.0 / 36, tet10_midside_mass = 4.0 / 27;

struct Tet10Geometry {
  double volume = 0;                                 ///< signed, of the corners' tetrahedron
  std::array<Eigen::Matrix<double, 10, 3>, 4> grad;  ///< per Gauss point, row a = grad N_a
};

using Tet10Matrix = Eigen::Matrix<double, 30, 30>;  ///< dof order: node a, component i -> 3a + i

Tet10Geometry tet10_geometry(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);
/// The 10 shape functions at barycentric coordinates L (summing to 1).
Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector4d& L);
/// The 3x3 block K_ab (rows: node a's components, columns: node b's).
Mat3 tet10_stiffness_block(const Tet10Geometry& g, const Material& m, int a, int b);
Tet10Matrix tet10_stiffness(const Tet10Geometry& g, const Material& m);

}  // namespace roifem::fem
