// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/material.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "fem/ogden.hpp"

namespace {
std::string str(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}
}  // namespace

namespace roifem::fem {

namespace {

/// Budday et al. (2017)'s four regions, their one-term Ogden fits (docs/materials.md's fit table).
struct MeasuredRegion {
  std::string_view name;
  double mu;     ///< Pa
  double alpha;  ///< dimensionless
};
constexpr MeasuredRegion measured_regions[] = {
    {"cortex", 1501.0, -18.17},
    {"basal-ganglia", 730.0, -17.99},
    {"corona-radiata", 702.0, -23.64},
    {"corpus-callosum", 374.0, -24.98},
};

}  // namespace

Material Material::from_young_poisson(double young, double poisson, double rho, double alpha) {
  if (!(young > 0) || !std::isfinite(young))
    throw InputError("material: Young's modulus E = " + str(young) + " Pa must be positive and finite");
  if (!(poisson > -1.0 && poisson < 0.5))
    throw InputError("material: Poisson's ratio nu = " + str(poisson) + " must lie in (-1, 0.5)");
  Material m;
  m.lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson));
  m.mu = young / (2 * (1 + poisson));
  m.rho = rho;
  m.alpha = alpha;
  m.validate();
  return m;
}

void Material::validate() const {
  auto finite = [](double v, const char* name) {
    if (!std::isfinite(v)) throw InputError(std::string("material: ") + name + " is NaN or infinite");
  };
  finite(lambda, "lambda");
  finite(mu, "mu");
  finite(rho, "rho");
  finite(alpha, "alpha");
  if (!(mu > 0)) throw InputError("material: shear modulus mu = " + str(mu) + " Pa must be positive");
  // nu in (-1, 0.5) <=> mu > 0 and 3 lambda + 2 mu > 0 (positive bulk modulus); nu -> 0.5 as lambda -> inf.
  if (!(3 * lambda + 2 * mu > 0))
    throw InputError("material: Poisson's ratio nu = " + str(poisson()) + " must lie in (-1, 0.5) (lambda = " + str(lambda) +
                     " Pa is too negative)");
  if (!(rho > 0)) throw InputError("material: density rho = " + str(rho) + " kg/m^3 must be positive");
  if (!(alpha >= 0)) throw InputError("material: damping alpha = " + str(alpha) + " 1/s must be >= 0");
  validate_law();
}

void Material::validate_law() const {
  if (model != MaterialModel::ogden) {
    if (!ogden.empty())
      throw InputError("material: Ogden terms (ogden_alpha) given to the " + std::string(material_model_name(model)) +
                       " law; they are the ogden law's (model = \"ogden\")");
    return;
  }
  const Ogden law = Ogden::of(*this);  // names a term outside its domain
  if (std::abs(law.mu() - mu) > 1e-12 * mu)
    throw InputError("material: the Ogden terms' mu_i sum to " + str(law.mu()) + " Pa, not to the shear modulus mu = " + str(mu) +
                     " Pa");
}

Material material_preset(std::string_view name) {
  if (name == "paper") {
    // Table 1 gives lambda = 0.4 and mu = 0.0012 "in units of 1e5 kg/cm^2" with rho = 1.0 g/cm^3.
    // Read as consistent cm-g-s units (1 dyn/cm^2 = 0.1 Pa) this is lambda = 4e4 dyn/cm^2 and
    // mu = 120 dyn/cm^2; the lowest eigenfrequency of the 800-node brain is then about 2 rad/s and
    // alpha = 0.8 1/s settles the response in about 50 steps of 0.05 s, as the paper's error curves show.
    Material m{.lambda = 0.4e5 * 0.1, .mu = 0.0012e5 * 0.1, .rho = 1000.0, .alpha = 0.8};
    m.validate();
    return m;
  }
  if (name == "brain") {
    // Shear modulus about 1 kPa (Budday et al. 2017, Acta Biomater. 48:319, human grey/white matter
    // 0.7-1.9 kPa); nu = 0.45 keeps linear tetrahedra clear of volumetric locking; density
    // 1040 kg/m^3 (Barber et al. 1970). alpha = 5 1/s is a modelling choice, not a measured value.
    const double mu = 1000.0, nu = 0.45;
    return Material::from_young_poisson(2 * mu * (1 + nu), nu, 1040.0, 5.0);
  }
  for (const MeasuredRegion& region : measured_regions)
    if (name == region.name) {
      // One Ogden term as `roifem fit data/budday2017-brain.csv` finds it, at the fit's bulk
      // modulus kappa = 1000 mu (nu = 0.4995); density and damping as the brain preset's.
      Material m{.lambda = (1000.0 - 2.0 / 3.0) * region.mu,
                 .mu = region.mu,
                 .rho = 1040.0,
                 .alpha = 5.0,
                 .model = MaterialModel::ogden,
                 .ogden = {{.mu = region.mu, .alpha = region.alpha}}};
      m.validate();
      return m;
    }
  std::vector<std::string> names = {"paper", "brain"};
  for (const MeasuredRegion& region : measured_regions) names.emplace_back(region.name);
  std::string valid;
  for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("material preset '" + std::string(name) + "' is unknown" + did_you_mean(name, names) + " (valid: " + valid +
                   ")");
}

}  // namespace roifem::fem
