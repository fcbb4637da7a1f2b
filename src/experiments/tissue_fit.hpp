// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// roifem fit: a hyperelastic law's parameters fitted by least squares to measured tissue curves
/// (experiments/tissue_data.hpp), region by region, all of a region's modes at once. Each model
/// point is the project's own law on the test's homogeneous deformation
/// (experiments/homogeneous_response.hpp). The laws: one-term Ogden (mu, alpha) and neo-Hookean
/// (mu), nearly incompressible at a fixed kappa / mu. GSL's trust-region Levenberg-Marquardt
/// (gsl_multifit_nlinear) from several starts, the best kept.
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "experiments/tissue_data.hpp"
#include "fem/material.hpp"

namespace roifem::experiments {

struct TissueFitOptions {
  std::filesystem::path data;
  std::vector<std::string> laws{"ogden", "neo-hookean"};
  double bulk_ratio = 1000;  ///< kappa / mu, held during the fit
  int max_iterations = 200;  ///< per start
  std::filesystem::path out;
};

struct LawFit {
  std::string region;
  std::string law;  ///< "ogden" or "neo-hookean"
  double mu_Pa = 0;
  double alpha = 0;  ///< Ogden's exponent (2 for neo-Hookean)
  double lambda_Pa = 0;
  std::map<TissueMode, double> rmse_Pa;  ///< per mode present
  double rmse_all_Pa = 0;
  int points = 0;
  int iterations = 0;
  bool converged = false;
  std::string stop_reason;  ///< GSL's, where not converged
};

/// The material a fit stands for: the brain preset's density and damping, the law and moduli.
fem::Material fitted_material(const LawFit& fit, double bulk_ratio);

/// Model stress (Pa) of `material`'s law at a curve's deformations.
std::vector<double> model_stress(const fem::Material& material, const TissueCurve& curve);

/// One region's fit of one law (InputError if the region has fewer points than the law has
/// parameters).
LawFit fit_region(const std::vector<TissueCurve>& curves, const std::string& region, const std::string& law,
                  const TissueFitOptions& options);

/// The command: reads, fits every region with every law, prints the table, writes DIR/fit.csv,
/// DIR/fit_curves.csv, DIR/fit_data.csv, DIR/material-REGION-LAW.toml and DIR/fit-REGION.png.
/// SolverError after writing them when a fit did not converge (its best parameters kept).
void run_tissue_fit(const TissueFitOptions& options, std::ostream& out);

}  // namespace roifem::experiments
