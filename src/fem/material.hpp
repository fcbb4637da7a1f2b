// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Isotropic linear elasticity with mass density and mass-proportional (Rayleigh alpha) damping:
///   sigma = lambda tr(eps) I + 2 mu eps,   C = alpha M.
/// SI units: lambda, mu in Pa; rho in kg/m^3; alpha in 1/s.
#include <string>
#include <string_view>
#include <vector>

#include "fem/material_model.hpp"
#include "fem/ogden_term.hpp"

namespace roifem::fem {

struct Material {
  double lambda = 0;  ///< Pa
  double mu = 0;      ///< Pa (shear modulus)
  double rho = 0;     ///< kg/m^3
  double alpha = 0;   ///< 1/s, C = alpha M
  /// The constitutive law (fem/material_model.hpp); lambda and mu are its small-strain moduli.
  MaterialModel model = MaterialModel::linear;
  /// The Ogden law's terms (model ogden only): their mu_i sum to mu, the small-strain shear modulus.
  std::vector<OgdenTerm> ogden;

  static Material from_young_poisson(double young, double poisson, double rho, double alpha);
  double young() const { return mu * (3 * lambda + 2 * mu) / (lambda + mu); }
  double poisson() const { return lambda / (2 * (lambda + mu)); }

  /// Throws InputError naming the parameter: E <= 0, nu outside (-1, 0.5), rho <= 0, alpha < 0, NaN;
  /// for the Ogden law a term's mu_i <= 0 or alpha_i = 0, or terms whose mu_i do not sum to mu; Ogden
  /// terms given to another law.
  void validate() const;

 private:
  void validate_law() const;
};

/// Named presets:
///  "paper": Hansen & Larsen (1998) Table 1 read in cm-g-s units: lambda = 0.4e5 dyn/cm^2 = 4000 Pa,
///           mu = 0.0012e5 dyn/cm^2 = 12 Pa, rho = 1 g/cm^3, alpha = 0.8 1/s.
///  "brain": literature values, see README.md: mu = 1 kPa, nu = 0.45, rho = 1040 kg/m^3, alpha = 5 1/s.
///  "cortex", "basal-ganglia", "corona-radiata", "corpus-callosum": human brain tissue as Budday et
///           al. (2017) measured it, one Ogden term each fitted by `roifem fit` to their tension,
///           compression and shear curves (data/budday2017-brain.csv), nearly incompressible
///           (kappa = 1000 mu), rho = 1040 kg/m^3, alpha = 5 1/s (docs/materials.md).
/// Unknown names throw InputError listing the presets.
Material material_preset(std::string_view name);

}  // namespace roifem::fem
