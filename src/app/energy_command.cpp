// SPDX-License-Identifier: GPL-3.0-or-later
// roifem energy SCENARIO.toml --out DIR
#include <iostream>

#include "app/commands.hpp"
#include "experiments/energy_study.hpp"
#include "integrators/integrator_table.hpp"
#include "scenario/scenario.hpp"

namespace roifem::app {

void add_energy_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario;
    experiments::EnergyStudyOptions energy;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "energy",
      "Run each integrator on one scenario and track its energy balance E + D = W (kinetic + strain energy + what damping "
      "took = the loads' work) over time: on an undamped scenario (alpha_per_s = 0), how far each method drifts. Writes "
      "energy_summary.csv, energy.csv and energy_error.png");
  cmd->add_option("SCENARIO", o->scenario,
                  "Scenario file (.toml); its dt is the step of the fixed-step methods and the output grid")
      ->required();
  cmd->footer(integrators::integrator_table_text());
  cmd->add_option("--out", o->energy.out, "Output directory")->required();
  cmd->add_option("--integrators", o->energy.integrators, "Only these integrators (default: every one that takes the model)");
  cmd->add_option("--t-end", o->energy.t_end, "Simulated time in s (0: the scenario's dt * steps)")->capture_default_str();
  cmd->add_option("--rtol", o->energy.rtol, "Relative tolerance of the explicit and adaptive-only methods (atol = rtol x 1 mm)")
      ->capture_default_str();
  cmd->add_option("--max-run-seconds", o->energy.max_run_s, "Stop a run taking longer (its outputs so far are kept)")
      ->capture_default_str();
  cmd->add_flag("!--no-plots", o->energy.plots, "Skip the PNG plot");
  cmd->callback([&action, o] {
    action = [o] { experiments::run_energy_study(scenario::read_scenario(o->scenario), o->energy, std::cout); };
  });
}

}  // namespace roifem::app
