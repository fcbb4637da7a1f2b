// SPDX-License-Identifier: GPL-3.0-or-later
// roifem run SCENARIO.toml --out DIR
#include <iostream>

#include "app/commands.hpp"
#include "integrators/integrator_table.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_run.hpp"

namespace roifem::app {

void add_run_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario, out;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("run",
                                 "Run one scenario (TOML: mesh, material, fixed sets, loads with ramps, ROI, "
                                 "integrator, dt, steps, optional rtol / atol for error-controlled steps, outputs; see "
                                 "scenarios/README.md) and write DIR/results.h5 and DIR/results.xdmf; prints the peak "
                                 "displacement and warns when it makes no physical sense");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml)")->required();
  cmd->footer(integrators::integrator_table_text());
  cmd->add_option("--out", o->out, "Output directory")->required();
  cmd->callback(
      [&action, o] { action = [o] { simulation::run_scenario(scenario::read_scenario(o->scenario), o->out, std::cout); }; });
}

}  // namespace roifem::app
