// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A hyperelastic tetrahedron (fem/hyperelastic_law.hpp: neo-Hookean, Ogden): its internal force and consistent tangent at the
/// nodal displacements u_e, by the quadrature of the linear one (tet4: one point, exact for its
/// constant gradients) or of the quadratic one (tet10: 4 Gauss points, as CalculiX's C3D10):
///   F_q = I + sum_a u_a g_a^T,      f_a = sum_q w_q P(F_q) g_a,
///   K_ab(i, k) = sum_q w_q sum_{J,L} A_iJkL(F_q) g_aJ g_bL,
/// with g_a the reference gradients of N_a at point q and w_q its share of the reference volume.
/// The energy is sum_q w_q W(F_q), so f = dE/du_e and K = df/du_e (the tests check both by
/// finite differences). Dof order: node a, component i -> 3a + i, as the linear elements'.
#include "common/types.hpp"
#include "fem/discrete_gradient.hpp"
#include "fem/hyperelastic_law.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/tet10.hpp"
#include "fem/tet4.hpp"

namespace roifem::fem {

template <int Nodes>
struct HyperelasticResponse {
  Eigen::Matrix<double, 3 * Nodes, 1> force;
  Eigen::Matrix<double, 3 * Nodes, 3 * Nodes> tangent;  ///< filled when asked for
  double energy = 0;                                    ///< J, when asked for (Evaluate::energy)
  /// The smallest det F over the quadrature points. At or below zero the element has inverted:
  /// force, tangent and energy are then not computed.
  double min_J = 1;
};

/// What an evaluation computes:
///  - force: f;
///  - energy: f and the energy;
///  - excess: what the law's force exceeds the linear element's by, f - K_lin u_e, K_lin the
///    linear element of the same lambda and mu (the law's tangent at rest), formed as the stress
///    difference P(F) - sigma_lin(H) at each point (NeoHookean::excess_stress), so that no element
///    matrix is formed: what a haptic tick iterates on (integrators/haptic_trapezoid.hpp);
///  - force_and_tangent: f and K.
enum class Evaluate { force, energy, excess, force_and_tangent };

/// Law: NeoHookean or Ogden (instantiated for each).
template <class Law>
HyperelasticResponse<4> tet4_hyperelastic(const Tet4Geometry& g, const Law& law, const Eigen::Matrix<double, 12, 1>& u_e,
                                          Evaluate what);
/// The neo-Hookean tet4's excess force alone (Evaluate::excess): the stress difference from H's cofactors,
/// J^(-2/3) by a cube root, no element matrix (a haptic tick's loop runs the same arithmetic eight
/// elements at a time: fem/tet4_excess_batch.hpp). Returns det F; at or below zero the element has
/// inverted and `excess` is left as it was.
double tet4_excess_force(const Tet4Geometry& g, const NeoHookean& law, const Eigen::Matrix<double, 12, 1>& u_e,
                         Eigen::Matrix<double, 12, 1>& excess);
template <class Law>
HyperelasticResponse<10> tet10_hyperelastic(const Tet10Geometry& g, const Law& law, const Eigen::Matrix<double, 30, 1>& u_e,
                                            Evaluate what);

/// The algorithmic force between the nodal displacements u_a and u_b (fem/discrete_gradient.hpp),
/// by the same quadrature: f = sum_q w_q F_mid S_alg g_a, so that f . (u_b - u_a) equals the
/// energy at u_b less that at u_a. `energy` is the energy at u_b, `min_J` the smaller over both
/// states (C_mid, a mean of two positive definite C, is one too); the tangent, when asked for, is
/// df/du_b (not symmetric: fem/discrete_gradient.hpp's D, and dF_mid = dF_b/2 against dE_b's F_b).
template <class Law>
HyperelasticResponse<4> tet4_discrete_gradient(const Tet4Geometry& g, const Law& law, const Eigen::Matrix<double, 12, 1>& u_a,
                                               const Eigen::Matrix<double, 12, 1>& u_b, Evaluate what = Evaluate::force);
template <class Law>
HyperelasticResponse<10> tet10_discrete_gradient(const Tet10Geometry& g, const Law& law, const Eigen::Matrix<double, 30, 1>& u_a,
                                                 const Eigen::Matrix<double, 30, 1>& u_b, Evaluate what = Evaluate::force);

}  // namespace roifem::fem
