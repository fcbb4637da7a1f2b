// SPDX-License-Identifier: GPL-3.0-or-later
// roifem-mpi: the full dynamic model and the ROI's condensation on P ranks (PETSc, MPI, MUMPS).
// CLI only: the work is src/distributed's. Run under MPI:
//   mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi
//   mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi -- -ksp_type cg -pc_type gamg
//   mpirun -n 2 roifem-mpi condense scenarios/paper-setup1.toml --out results/condensed --check
// Everything after -- goes to PETSc's options database.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include "common/errors.hpp"
#include "common/version.hpp"
#include "distributed/distributed_condense.hpp"
#include "distributed/distributed_model.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/petsc_handle.hpp"
#include "distributed/petsc_ts.hpp"
#include "distributed/root_work.hpp"
#include "experiments/compare_experiment.hpp"

namespace {

namespace distributed = roifem::distributed;

int run_cli(int argc, char** argv) {
  // `roifem-mpi --check-args COMMAND ...` parses and checks a command line and does nothing (the
  // docs check), before MPI or PETSc start.
  const bool check_only = argc > 1 && std::strcmp(argv[1], "--check-args") == 0;
  if (check_only) {
    for (int i = 1; i + 1 < argc; ++i) argv[i] = argv[i + 1];
    argv[--argc] = nullptr;
  }
  // roifem-mpi's own arguments before --, PETSc's after it.
  const auto separator = std::find_if(argv, argv + argc, [](const char* a) { return std::strcmp(a, "--") == 0; });
  const int own_argc = static_cast<int>(separator - argv);
  std::vector<char*> petsc_argv{argv[0]};
  if (separator != argv + argc) petsc_argv.insert(petsc_argv.end(), separator + 1, argv + argc);
  petsc_argv.push_back(nullptr);

  CLI::App app{
      "roifem-mpi: the full dynamic model of a scenario and its ROI's static condensation on P ranks (PETSc, MPI, MUMPS).\n"
      "Run under MPI; options after -- go to PETSc, e.g. the solver of K + 2/dt C + 4/dt^2 M:\n"
      "  mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi                  (MUMPS Cholesky)\n"
      "  mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi -- -ksp_type cg -pc_type gamg -ksp_rtol 1e-10\n"
      "  mpirun -n 2 roifem-mpi condense scenarios/paper-setup1.toml --out results/condensed --check\n"
      "  roifem-mpi compare scenarios/paper-setup1.toml --out results/compare-petsc                 (one rank)",
      "roifem-mpi"};
  app.set_version_flag("--version", "roifem-mpi " + std::string(roifem::version()), "Print the version and exit");
  app.require_subcommand(1);
  std::filesystem::path scenario_file, out = "results/mpi";
  bool check_serial = false;
  auto* run =
      app.add_subcommand("run", "Integrate the scenario's full model (every free node dynamic) with the trapezoidal rule");
  run->add_option("scenario", scenario_file, "Scenario file (TOML; its mesh, material, supports, loads, dt and steps)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out", out, "Directory for results.h5 and results.xdmf")->capture_default_str();
  roifem::experiments::CompareOptions compare_options;
  auto* compare = app.add_subcommand(
      "compare", "roifem compare with PETSc's integrators added (petsc-alpha2: TSALPHA2, petsc-theta: TSTHETA); one rank");
  compare->add_option("scenario", scenario_file, "Scenario file (.toml); its dt is the output grid")
      ->required()
      ->check(CLI::ExistingFile);
  compare->add_option("--out", compare_options.out, "Output directory")->required();
  compare->add_option("--integrators", compare_options.integrators,
                      "Only these (default: trapezoid, petsc-alpha2, petsc-theta; any of roifem compare's names too)");
  compare->add_option("--t-end", compare_options.t_end, "Simulated time in s (0: the scenario's dt * steps)")
      ->capture_default_str();
  compare->add_option("--fixed-levels", compare_options.fixed_levels, "Fixed steps dt, dt/2, ...")->capture_default_str();
  compare->add_flag("!--no-plots", compare_options.plots, "Skip the PNG plots");
  auto* cond = app.add_subcommand("condense", "Condense the scenario's [roi] from the distributed K by MUMPS's Schur complement");
  cond->add_option("scenario", scenario_file, "Scenario file with an [roi]")->required()->check(CLI::ExistingFile);
  cond->add_option("--out", out, "Directory for condensation.h5")->capture_default_str();
  cond->add_flag("--check", check_serial, "Also condense serially on rank 0 and print the differences");
  try {
    app.parse(own_argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (check_only) return 0;
  try {
    const distributed::PetscSession session(static_cast<int>(petsc_argv.size()) - 1, petsc_argv.data());
    try {
      // Read and checked alike on every rank: a refusal is printed once, with no MPI_Abort.
      roifem::scenario::Scenario sc;
      distributed::on_every_rank(session.comm(), [&] {
        sc = roifem::scenario::read_scenario(scenario_file);
        if (!compare->parsed()) distributed::check_distributable(sc);
      });
      if (run->parsed()) {
        distributed::run_distributed(sc, out, std::cout, session.comm());
      } else if (compare->parsed()) {
        if (session.size() > 1)
          throw roifem::InputError("roifem-mpi compare runs on one rank (PETSc's integrators on PETSC_COMM_SELF)");
        compare_options.extra_rows = distributed::petsc_ts_rows();
        if (compare_options.integrators.empty()) compare_options.integrators = {"trapezoid", "petsc-alpha2", "petsc-theta"};
        roifem::experiments::run_compare(sc, compare_options, std::cout);
        distributed::check_options_used("by PETSc's integrators over the whole sweep");
      } else {
        distributed::condense_distributed(sc, out, check_serial, std::cout, session.comm());
      }
    } catch (const std::exception& e) {
      if (dynamic_cast<const distributed::AgreedByEveryRank*>(&e) != nullptr) {  // every rank is here: say it once
        if (session.rank() == 0)
          std::cerr << "roifem-mpi: " << (dynamic_cast<const roifem::Interrupted*>(&e) ? "" : "error: ") << e.what() << '\n';
        const auto* interrupted = dynamic_cast<const roifem::Interrupted*>(&e);
        return interrupted != nullptr ? 128 + interrupted->signal : 1;
      }
      // One rank's failure must not leave the others waiting in a collective call: stop them all.
      std::cerr << "roifem-mpi: error (rank " << session.rank() << "): " << e.what() << '\n';
      std::cerr.flush();
      std::cout.flush();
      if (session.size() > 1) MPI_Abort(session.comm(), 1);
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "roifem-mpi: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_cli(argc, argv);
  } catch (const std::exception& e) {  // before or after the PETSc session (CLI11's set-up, PetscFinalize)
    std::cerr << "roifem-mpi: error: " << e.what() << '\n';
    return 1;
  }
}
