// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Command-line misuse that CLI11 reports too vaguely: an unknown command (it says "A subcommand is
/// required") and an unknown long option (it reports a missing positional first, so
/// `run --hlep` says "SCENARIO is required"). Checked before parsing, with a "did you mean".
#include <CLI/CLI.hpp>
#include <string>

#include "app/commands.hpp"

namespace roifem::app {

/// The message for the first misuse in argv, or "" when CLI11 may parse it.
std::string find_misuse(CLI::App& app, int argc, const char* const* argv);

/// Removes a leading --check-args from argv (argc one less) and says whether it was there: the
/// command line is then parsed and checked (options, values, input files), and nothing runs.
bool take_check_args(int& argc, char** argv);

/// `roifem help [COMMAND]`: the app's or the command's --help text.
void add_help_command(CLI::App& app, Action& action);

}  // namespace roifem::app
