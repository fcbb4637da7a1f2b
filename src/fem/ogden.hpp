// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The compressible N-term Ogden law in CalculiX's form (*HYPERELASTIC, OGDEN, N=...), total
/// Lagrangian, as a function of the displacement gradient H = Grad u (F = I + H):
///   W = sum_i 2 mu_i / alpha_i^2 (lbar_1^alpha_i + lbar_2^alpha_i + lbar_3^alpha_i - 3) + (J - 1)^2 / D1,
/// lbar_k = J^(-1/3) lambda_k the isochoric principal stretches. Its small-strain shear modulus is
/// sum_i mu_i and its bulk modulus kappa = 2/D1; one term with alpha = 2 is the neo-Hookean law
/// (fem/neo_hookean.hpp) with mu = mu_1. Brain tissue: alpha near -20 makes compression several
/// times stiffer than tension (Budday et al. 2017).
///
/// How it keeps its digits. With E = (H + H^T + H^T H)/2 (formed from H) and its eigenvalues e_k,
/// every power of C = I + 2E is I plus a function of E that vanishes at rest,
///   C^p = I + G_p(E),  G_p = sum_k g_p(e_k) N_k N_k^T,  g_p(e) = (1 + 2e)^p - 1 = expm1(p log1p(2e)),
/// so the isochoric stress
///   S = sum_i (2 mu_i / alpha_i) J^(-alpha_i/3) [C^(a_i - 1) - tr(C^(a_i)) / 3 C^-1],  a_i = alpha_i / 2,
/// is formed from terms O(|E|) with no difference of O(1) terms, and the energy from the deviatoric
/// logarithmic stretches d_k = log lambda_k - log J / 3 (their sum set to zero) as
/// sum_k (expm1(alpha d_k) - alpha d_k) >= 0. The tangent differentiates each G_p by Daleckii and
/// Krein's formula, dG_p[dE] = sum_{k,l} g_p[e_k, e_l] N_k N_k^T dE N_l N_l^T, whose divided
/// differences g_p[x, y] = (g_p(x) - g_p(y)) / (x - y) are formed as 2 c_y^(p - 1) expm1(p t) /
/// expm1(t), t = log(c_x / c_y): equal and nearly equal eigenvalues (the state at rest among them)
/// give the derivative's limit, with no NaN and no loss of digits.
/// W, S, P and their tangents are finite only for J > 0; callers check J first.
#include <vector>

#include "common/types.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/ogden_term.hpp"

namespace roifem::fem {

class Ogden {
 public:
  /// InputError naming the term and the parameter outside its domain (mu_i <= 0, alpha_i = 0 or not
  /// finite, D1 <= 0, no term).
  Ogden(std::vector<OgdenTerm> terms, double D1);
  /// A material's law (model ogden): its terms, D1 = 2/kappa with kappa = lambda + 2 mu / 3.
  static Ogden of(const Material& material);

  const std::vector<OgdenTerm>& terms() const { return terms_; }
  double D1() const { return D1_; }
  /// The small-strain shear modulus, sum_i mu_i (Pa).
  double mu() const;
  double kappa() const { return 2 / D1_; }
  /// The same terms with no volumetric part (kappa = 0): the deviatoric energy and stress, which
  /// the discrete gradient projects (fem/discrete_gradient.hpp).
  Ogden deviatoric_part() const;

  /// Strain energy density (J/m^3).
  double energy(const Mat3& H) const;
  /// First Piola-Kirchhoff stress P = F S (Pa).
  Mat3 stress(const Mat3& H) const;
  /// P less the linear law's stress at the same gradient (lambda = kappa - 2 mu / 3): O(|H|^2).
  Mat3 excess_stress(const Mat3& H) const;
  /// P and A = dP/dF (a 9x9 matrix over the flattened F, entry (i, J) at 3 i + J) in one pass.
  void stress_and_tangent(const Mat3& H, Mat3& P, Mat9& A) const;
  /// The second Piola-Kirchhoff stress S = 2 dW/dC as a function of the Green-Lagrange strain E.
  Mat3 stress_of_strain(const Mat3& E) const;
  /// dS/dE (Pa), 9x9 over the flattened E, symmetric and minor-symmetric.
  Mat9 strain_tangent(const Mat3& E) const;

 private:
  std::vector<OgdenTerm> terms_;
  double D1_ = 0;
};

}  // namespace roifem::fem
