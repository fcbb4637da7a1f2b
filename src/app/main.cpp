// SPDX-License-Identifier: GPL-3.0-or-later
// roifem: region-of-interest finite element models of the brain for surgery simulation.
// CLI only: every sub-command lives in a *_commands.cpp file and calls the libraries.
#include <cstdlib>
#include <iostream>

#include "app/commands.hpp"
#include "app/misuse.hpp"
#include "common/errors.hpp"
#include "common/version.hpp"

namespace {

int run_cli(int argc, char** argv) {
  // `roifem --check-args COMMAND ...` parses a command line, checks it and does nothing (the docs
  // check runs every command line the guide quotes this way); not in --help.
  const bool check_only = roifem::app::take_check_args(argc, argv);
  CLI::App app{
      "roifem: region-of-interest (ROI) finite element models of the brain for surgery simulation.\n"
      "A linear-elastic tetrahedral brain whose ROI is dynamic and whose rest is condensed statically.\n"
      "Start with:  roifem paper --out results/paper   (the Hansen & Larsen 1998 experiment)\n"
      "Lengths on the command line and in files are millimetres; inside, everything is SI.",
      "roifem"};
  app.set_version_flag("--version", "roifem " + std::string(roifem::version()), "Print the version and exit");
  app.footer(
      "Exit codes: 0 done; 1 an error in the input, the model or a solver (the message names the file, key,\n"
      "node, element or step); 2 a command-line error; 130 / 143 stopped by Ctrl-C / SIGTERM (every completed\n"
      "step kept).");
  app.require_subcommand(1);
  roifem::app::Action action;
  roifem::app::add_mesh_command(app, action);
  roifem::app::add_info_command(app, action);
  roifem::app::add_run_command(app, action);
  roifem::app::add_compare_command(app, action);
  roifem::app::add_energy_command(app, action);
  roifem::app::add_paper_command(app, action);
  roifem::app::add_roi_size_command(app, action);
  roifem::app::add_convergence_command(app, action);
  roifem::app::add_model_error_command(app, action);
  roifem::app::add_fit_command(app, action);
  roifem::app::add_serve_command(app, action);
  roifem::app::add_help_command(app, action);
  if (const std::string misuse = roifem::app::find_misuse(app, argc, argv); !misuse.empty()) {
    std::cerr << "roifem: " << misuse << '\n';
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help is a success; every other parse error is misuse
  }
  if (check_only) return 0;
  try {
    action();
  } catch (const CLI::ValidationError& e) {  // `roifem help NAME` with an unknown NAME
    std::cerr << "roifem: " << e.what() << '\n';
    return 2;
  } catch (const roifem::Interrupted& e) {
    std::cerr << "roifem: " << e.what() << '\n';
    return 128 + e.signal;
  } catch (const std::exception& e) {
    std::cerr << "roifem: error: " << e.what() << '\n';
    // Every file is closed or discarded by now (RAII). Skip the atexit handlers: after a failed
    // write (disk full), HDF5 1.10's own shutdown retries the flush and crashes.
    std::cout.flush();
    std::cerr.flush();
    std::_Exit(1);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_cli(argc, argv);
  } catch (...) {  // building the CLI itself failed (out of memory): nothing to clean up yet
    std::cerr << "roifem: error: could not start\n";
    return 1;
  }
}
