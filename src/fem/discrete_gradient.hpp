// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A discrete gradient of a hyperelastic law (fem/hyperelastic_law.hpp: neo-Hookean, Ogden) (O. Gonzalez, "Exact energy and
/// momentum conserving algorithms for general models in nonlinear elasticity", CMAME 190, 2000): the stress between two states a
/// and b whose work on the strain increment is exactly the energy increment, S_alg : dE = W(b) - W(a) for any two states, dE =
/// E_b - E_a. The law's two parts, its deviatoric energy (neo-Hookean's C10 (I1bar - 3), Ogden's sum over its terms) and the
/// volumetric (J - 1)^2 / D1 that both share, take one each:
///  - the deviatoric part, Gonzalez's projection:
///      S_dev,alg = S_dev(E_mid) + [W_dev(b) - W_dev(a) - S_dev(E_mid) : dE] dE / (dE : dE),
///    E_mid = (E_a + E_b)/2;
///  - the volumetric part, its own discrete gradient in J:
///      S_vol,alg = kappa (J_mid - 1) / J_mid G,   G = (cof C_a + 4 cof C_mid + cof C_b) / 6,
///    J_mid = (J_a + J_b)/2, C_mid = (C_a + C_b)/2: cof C is quadratic along C_a + s (C_b - C_a),
///    so Simpson's rule makes G : (C_b - C_a) = det C_b - det C_a = J_b^2 - J_a^2 exactly, and
///    S_vol,alg : dE = kappa (J_mid - 1) (J_b - J_a) = [(J_b - 1)^2 - (J_a - 1)^2] / D1, with no
///    difference of energies. At a = b it is S_vol = kappa (J - 1) J C^-1.
/// Gonzalez's projection of the whole law (the first form alone) put the volumetric stiffness,
/// 333 times the shear's on the brain, into a correction along dE, and Newton on the paper brain
/// failed (docs/design-figures.md). A tetrahedron's algorithmic force is then f_a = int F_mid S_alg
/// g_a dV with F_mid = (F_a + F_b)/2: because E_b - E_a = sym(F_mid^T (F_b - F_a)) exactly, its
/// work on the nodal increment is the element's energy increment, and, S_alg being symmetric and
/// F_mid a mean, it conserves angular momentum too (fem/hyperelastic_element.hpp,
/// integrators/energy_momentum.hpp).
///
/// The projection's numerator c = W(b) - W(a) - S(E_mid) : dE (the deviatoric part's) is
/// O(|dE|^3), a difference of nearly equal numbers, computed in three ways by the size of dE:
///  - |dE| >= large_increment: the energies' difference; its rounding, eps W, puts eps W / |dE|
///    into the stress, under 1e3 eps W.
///  - below: int_0^1 (S(E_a + s dE) - S(E_mid)) : dE ds by 3-point Gauss-Legendre, whose rounding
///    puts eps |S| into the stress and whose quadrature error, O(|d^6 S| |dE|^7), is far below
///    rounding there. (The energies' difference alone put 1e-7 mu of noise into the stress at
///    |dE| = 1e-8, and on the paper brain, whose far elements barely strain in a step, stalled
///    Newton six orders above its tolerance.)
///  - |dE| < negligible_increment: none, S_alg = S(E_mid). The quadrature's second difference of S
///    is then mostly rounding, and the tangent's c / |dE|^2 terms, eps |S| / |dE|, would spoil
///    Newton's direction; the energy error left, O(|dC/dE| |dE|^3), is below 1e-21 of kappa per
///    unit volume, and the stress's jump at the threshold, O(|dC/dE| |dE|^2), below rounding.
/// Either way S_alg : dE = W(b) - W(a) to rounding.
#include "common/types.hpp"
#include "fem/neo_hookean.hpp"

namespace roifem::fem {

/// |dE| from which c is the energies' difference, not a quadrature (see above).
inline constexpr double large_increment = 1e-3;
/// |dE| below which S_alg is S(E_mid) (see above).
inline constexpr double negligible_increment = 1e-7;

/// The Green-Lagrange strain E = (H + H^T + H^T H)/2 of a displacement gradient H.
Mat3 green_lagrange(const Mat3& H);

/// S_alg between displacement gradients H_a and H_b (both with det F > 0), symmetric (Pa), for
/// Law NeoHookean or Ogden.
template <class Law>
Mat3 discrete_gradient_stress(const Law& law, const Mat3& H_a, const Mat3& H_b);
/// The same, and its derivative in the second state's strain: dS_alg = D . vec(dE_b) (9x9 over
/// the flattened strain, as the law's strain_tangent; not symmetric).
template <class Law>
Mat3 discrete_gradient_stress(const Law& law, const Mat3& H_a, const Mat3& H_b, Mat9& D);

}  // namespace roifem::fem
