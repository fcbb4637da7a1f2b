// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The compressible neo-Hookean law in CalculiX's form (*HYPERELASTIC, NEO HOOKE), total
/// Lagrangian, as a function of the displacement gradient H = Grad u (F = I + H):
///   W = C10 (I1bar - 3) + (J - 1)^2 / D1,   J = det F,  I1bar = J^(-2/3) tr(F^T F),
/// with C10 = mu/2 and D1 = 2/kappa, kappa = lambda + 2 mu/3 the bulk modulus (so that its
/// linearization at H = 0 is the linear law with the same lambda and mu). Its derivatives:
///   P = dW/dF = F^-T [mu J^(-2/3) dev C + kappa (J - 1) J I]    (first Piola-Kirchhoff)
///   A = dP/dF, a 9x9 matrix over the flattened F (entry (i, J) at 3 i + J, row-major), symmetric.
/// The law takes H, not F: a double holding 1 + 1e-9 keeps 7 of its digits, so F = I + H formed
/// first loses at small strain what no formula after it recovers. J - 1, dev C and I1bar - 3 are
/// formed from H without cancellation, so P and W keep their digits at any strain (the tests check
/// them at 1e-9 against the linear law).
/// W, P and A are finite only for J > 0; callers check J first (an inverted element).
#include <limits>

#include "common/types.hpp"
#include "fem/material.hpp"

namespace roifem::fem {

using Mat9 = Eigen::Matrix<double, 9, 9>;

struct NeoHookean {
  double C10 = 0;  ///< Pa, mu/2
  double D1 = 0;   ///< 1/Pa, 2/kappa

  /// C10 and D1 from a material's lambda and mu.
  static NeoHookean of(const Material& material);
  double mu() const { return 2 * C10; }
  double kappa() const { return 2 / D1; }
  /// The same C10 with no volumetric part (kappa = 0), as the discrete gradient projects it.
  NeoHookean deviatoric_part() const { return {.C10 = C10, .D1 = std::numeric_limits<double>::infinity()}; }

  /// J - 1 = det(I + H) - 1, without cancellation.
  static double J_minus_1(const Mat3& H);
  /// Strain energy density (J/m^3).
  double energy(const Mat3& H) const;
  /// First Piola-Kirchhoff stress P (Pa).
  Mat3 stress(const Mat3& H) const;
  /// P less the linear law's stress at the same gradient, P(H) - [lambda tr(H) I + mu (H + H^T)]
  /// with lambda = kappa - 2 mu/3 (the law's linearization at rest): what the law adds to the
  /// linear model, O(|H|^2).
  Mat3 excess_stress(const Mat3& H) const;
  /// P and its derivative A = dP/dF in one pass.
  void stress_and_tangent(const Mat3& H, Mat3& P, Mat9& A) const;
  /// The second Piola-Kirchhoff stress S = 2 dW/dC = C^-1 [mu J^(-2/3) dev C + kappa (J - 1) J I] (Pa)
  /// as a function of the Green-Lagrange strain E = (C - I)/2 (symmetric), formed without
  /// cancellation: at E = (H + H^T + H^T H)/2 it is F^-1 P(H). The discrete gradient
  /// (fem/discrete_gradient.hpp) evaluates it at a strain between two states, where no F is at hand.
  Mat3 stress_of_strain(const Mat3& E) const;
  /// Its derivative dS/dE (Pa), a 9x9 matrix over the flattened E (entry (I, J) at 3 I + J): with
  /// G = C^-1, a = J^(-2/3), I1 = tr C and (G o G)_IJKL = (G_IK G_JL + G_IL G_JK)/2,
  ///   dS/dE = 2/3 mu a [I1 G o G - G x I - I x G + I1/3 G x G] + kappa [(2J - 1) J G x G - 2 (J - 1) J G o G];
  /// symmetric, and minor-symmetric, so dS = dS/dE . vec(dE) for a symmetric dE.
  Mat9 strain_tangent(const Mat3& E) const;
};

}  // namespace roifem::fem
