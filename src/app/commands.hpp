// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Sub-commands of the roifem CLI. Each registers its options on the app and returns the action
/// that runs it; main() holds the single catch.
#include <CLI/CLI.hpp>
#include <functional>

namespace roifem::app {

using Action = std::function<void()>;

void add_mesh_command(CLI::App& app, Action& action);
void add_info_command(CLI::App& app, Action& action);
void add_paper_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_energy_command(CLI::App& app, Action& action);
void add_roi_size_command(CLI::App& app, Action& action);
void add_convergence_command(CLI::App& app, Action& action);
void add_model_error_command(CLI::App& app, Action& action);
void add_fit_command(CLI::App& app, Action& action);
void add_serve_command(CLI::App& app, Action& action);

}  // namespace roifem::app
