// SPDX-License-Identifier: GPL-3.0-or-later
// roifem run SCENARIO.toml --out DIR [--from DIR/results.h5 [--step K]]
#include <iostream>
#include <optional>

#include "app/commands.hpp"
#include "fem/material_model.hpp"
#include "integrators/integrator_table.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_run.hpp"

namespace roifem::app {

void add_run_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario, out, from;
    std::optional<long> step;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("run",
                                 "Run one scenario (TOML: mesh, material, fixed sets, loads with ramps, ROI, "
                                 "integrator, dt, steps, optional rtol / atol for error-controlled steps, outputs; see "
                                 "scenarios/README.md) and write DIR/results.h5 and DIR/results.xdmf; prints the peak "
                                 "displacement and warns when it makes no physical sense");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml)")->required();
  cmd->footer(integrators::integrator_table_text() + "\n" + fem::material_model_table_text());
  cmd->add_option("--out", o->out, "Output directory")->required();
  auto* from = cmd->add_option("--from", o->from,
                               "Go on from a restart point of an earlier run of the same scenario (its results.h5 or "
                               "results.incomplete.h5): its steps up to the point as it recorded them, then the rest; the "
                               "trapezoidal rule and energy-momentum go on bit for bit, the library methods afresh from u and v "
                               "(the scenario's [restart] table says the same)");
  cmd->add_option("--step", o->step,
                  "The restart point's step: a multiple of output.restart_every (default 10 x field_every), or a finished run's "
                  "last (default: the "
                  "last point the file holds)")
      ->needs(from);
  cmd->callback([&action, o] {
    action = [o] {
      scenario::Scenario sc = scenario::read_scenario(o->scenario);
      if (!o->from.empty()) sc.restart = scenario::Scenario::Restart{.from = o->from, .step = o->step, .where = ""};
      simulation::run_scenario(sc, o->out, std::cout);
    };
  });
}

}  // namespace roifem::app
