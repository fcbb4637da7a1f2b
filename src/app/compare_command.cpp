// SPDX-License-Identifier: GPL-3.0-or-later
// roifem compare SCENARIO.toml --out DIR
#include <iostream>

#include "app/commands.hpp"
#include "experiments/compare_experiment.hpp"
#include "integrators/integrator_table.hpp"
#include "scenario/scenario.hpp"

namespace roifem::app {

void add_compare_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario;
    experiments::CompareOptions compare;
  };
  auto o = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("compare",
                         "Run every integrator (trapezoid, ARKODE, IDA, GSL) on one scenario across fixed steps and tolerances, "
                         "measure true errors against the exact modal solution (without one, a nonlinear model or smooth "
                         "ramps: against a tight run of --reference checked by --reference-check), find stability limits; "
                         "writes compare.csv, stability.csv and work-precision plots");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml); its dt is the output grid")->required();
  cmd->footer(integrators::integrator_table_text());
  cmd->add_option("--out", o->compare.out, "Output directory")->required();
  cmd->add_option("--integrators", o->compare.integrators, "Only these integrators (default: all)");
  cmd->add_option("--t-end", o->compare.t_end, "Simulated time in s (0: the scenario's dt * steps)")->capture_default_str();
  cmd->add_option("--fixed-levels", o->compare.fixed_levels, "Fixed steps dt, dt/2, ... for the implicit methods")
      ->capture_default_str();
  cmd->add_option("--tolerances", o->compare.tolerances, "Relative tolerances for the adaptive runs");
  cmd->add_option("--max-steps", o->compare.max_steps, "Skip fixed-step runs needing more steps")->capture_default_str();
  cmd->add_option("--max-run-seconds", o->compare.max_run_s,
                  "Stop a run taking longer (and skip its tighter tolerances / smaller steps)")
      ->capture_default_str();
  cmd->add_flag("!--no-plots", o->compare.plots, "Skip the PNG plots");
  cmd->add_option("--reference", o->compare.reference,
                  "Without an exact modal solution: the method whose tight run every run is measured against")
      ->capture_default_str();
  cmd->add_option("--reference-check", o->compare.reference_check,
                  "The second method the reference is checked by, at the same tolerances (their difference is printed)")
      ->capture_default_str();
  cmd->add_option("--reference-rtol", o->compare.reference_rtol, "The reference's relative tolerance (atol: this x 1 mm)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback(
      [&action, o] { action = [o] { experiments::run_compare(scenario::read_scenario(o->scenario), o->compare, std::cout); }; });
}

}  // namespace roifem::app
