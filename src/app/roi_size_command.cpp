// SPDX-License-Identifier: GPL-3.0-or-later
// roifem roi-size SCENARIO.toml --max-error-mm E
#include <iostream>

#include "app/commands.hpp"
#include "experiments/roi_size.hpp"

namespace roifem::app {

void add_roi_size_command(CLI::App& app, Action& action) {
  struct Options {
    experiments::RoiSizeOptions size;
    std::vector<std::string> reductions{"static", "guyan", "craig-bampton-10"};
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "roi-size",
      "How large an ROI (the N nodes nearest the scenario's [roi] target) do I need? For each reduction of the "
      "static part: the size from which every larger ROI keeps its max error against the full dynamic model within "
      "the budget over the scenario's run (the error is not monotone in N: sizes that miss are reported), with the "
      "scenario's own ROI's error and the step cost. One progress line on a terminal; with --out, DIR/roi_size.csv "
      "and DIR/roi_size_runs.csv (every size tried) are rewritten after every run, so a stopped search keeps them");
  cmd->add_option("SCENARIO", o->size.scenario, "Scenario file (.toml) with [roi] kind = nearest or ball (its target)")
      ->required();
  cmd->add_option("--max-error-mm", o->size.max_error_mm,
                  "Error budget: max distance to the full model over ROI nodes and steps (mm)")
      ->required();
  cmd->add_option("--reductions", o->reductions, "Reductions to size: " + condensation::reduction_label_forms())
      ->capture_default_str();
  cmd->add_option("--integrator", o->size.integrator,
                  "Integrator of the full reference and of every ROI model, at the scenario's dt (the error "
                  "measured is then the reduction's alone); the scenario's own integrator is not used")
      ->capture_default_str();
  cmd->add_option("--start-nodes", o->size.start_nodes, "Smallest ROI tried (nodes)")->capture_default_str();
  cmd->add_option("--coarse", o->size.coarse, "Coarse grid of sizes: each the previous times (1 + this)")->capture_default_str();
  cmd->add_option("--resolution", o->size.resolution,
                  "Fine grid next to the answer: each size the previous times (1 + this), at least one node more")
      ->capture_default_str();
  cmd->add_option("--timing-steps", o->size.timing_steps,
                  "Steps timed for the step column (medians): the full model's, and each answer's")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o->size.out, "Output directory for roi_size.csv and roi_size_runs.csv (optional)");
  cmd->callback([&action, o] {
    action = [o] {
      o->size.reductions.clear();
      for (const auto& label : o->reductions) o->size.reductions.push_back(condensation::parse_reduction(label));
      experiments::run_roi_size(o->size, std::cout);
    };
  });
}

}  // namespace roifem::app
