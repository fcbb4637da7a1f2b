// SPDX-License-Identifier: GPL-3.0-or-later
// roifem fit DATA.csv --law ogden --out DIR
#include <iostream>

#include "app/commands.hpp"
#include "experiments/tissue_fit.hpp"

namespace roifem::app {

void add_fit_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<experiments::TissueFitOptions>();
  auto* cmd = app.add_subcommand(
      "fit",
      "Fit a hyperelastic law to measured tissue curves by least squares, region by region (all of a region's modes "
      "at once, each mode weighted alike): each model point is roifem's own law on the test's homogeneous deformation (uniaxial "
      "with the "
      "lateral faces free, simple shear exact), nearly incompressible at a fixed kappa / mu. Prints mu, alpha and the "
      "RMSE per region and mode; writes DIR/fit.csv, DIR/material-REGION-LAW.toml (a [material] table to paste into "
      "a scenario) and DIR/fit-REGION.png (data and fits). The shipped data: data/budday2017-brain.csv (human "
      "cortex, basal ganglia, corona radiata, corpus callosum; Budday et al. 2017)");
  cmd->add_option("DATA", o->data,
                  "Curves (.csv): columns region,mode,deformation,nominal_stress_kPa (or _Pa); mode tension, compression "
                  "(deformation: the stretch) or shear (the amount of shear); # starts a comment")
      ->required();
  cmd->add_option("--law", o->laws, "Laws to fit: ogden (one term: mu, alpha), neo-hookean (mu)")->capture_default_str();
  cmd->add_option("--bulk-ratio", o->bulk_ratio, "kappa / mu, held during the fit (1000: Poisson's ratio 0.4995)")
      ->capture_default_str();
  cmd->add_option("--max-iterations", o->max_iterations, "Levenberg-Marquardt iterations per start (5 starts for Ogden)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o->out, "Output directory")->required();
  cmd->callback([&action, o] { action = [o] { experiments::run_tissue_fit(*o, std::cout); }; });
}

}  // namespace roifem::app
