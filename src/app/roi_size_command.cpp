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
      "Find the smallest ROI (the N nodes nearest the scenario's [roi] target) whose max error against the full "
      "dynamic model stays within a budget over the scenario's run, for each reduction of the static part; "
      "prints size, error and step cost (and writes DIR/roi_size.csv with --out)");
  cmd->add_option("SCENARIO", o->size.scenario, "Scenario file (.toml) with [roi] kind = nearest or ball (its target)")
      ->required();
  cmd->add_option("--max-error-mm", o->size.max_error_mm,
                  "Error budget: max distance to the full model over ROI nodes and steps (mm)")
      ->required();
  cmd->add_option("--reductions", o->reductions, "Reductions to size: static, guyan, craig-bampton-K, pod-K")
      ->capture_default_str();
  cmd->add_option("--start-nodes", o->size.start_nodes, "Smallest ROI tried (nodes)")->capture_default_str();
  cmd->add_option("--out", o->size.out, "Output directory for roi_size.csv (optional)");
  cmd->callback([&action, o] {
    action = [o] {
      o->size.reductions.clear();
      for (const auto& label : o->reductions) o->size.reductions.push_back(condensation::parse_reduction(label));
      experiments::run_roi_size(o->size, std::cout);
    };
  });
}

}  // namespace roifem::app
